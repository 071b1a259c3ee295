// Acceptance of the ellipsoidal density-equalizing map (EDEM) on the shared
// meshes, part 1 (issue 5, item 4; the cases are in include/dem_edem_cases.h):
// edem_sphere, edem_ellipsoid1, edem_ellipsoid2 with their populations and
// radii (Var(normalized face density) <= 0.014, 0 fold-overs, on the
// ellipsoid), and area-preserving EDEM of maxplanck and twistedball onto
// (1, 0.8, 1.4) (mean |d_area| <= 0.05). Part 2: test_edem_elongated_shared.cpp.
// Skipped (77) when the shared data folder is not available.
#include <dem_edem_cases.h>

int main()
{
  using namespace dem_edem_cases;
  if(!data_available("edem_sphere.off")) {
    std::cout << "shared data not found in '" << data_dir() << "': skipped" << std::endl;
    return skip_code;
  }
  Stopwatch total;
  for(const char* name : {"edem_sphere", "edem_ellipsoid1", "edem_ellipsoid2"}) population_case(name);
  area_case("maxplanck");
  area_case("twistedball");
  std::cout << "total " << total.seconds() << " s" << std::endl;
  return finish("test_edem_shared");
}
