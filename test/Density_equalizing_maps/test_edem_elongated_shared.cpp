// Acceptance of the ellipsoidal density-equalizing map (EDEM) on the shared
// meshes, part 2 (issue 5, item 4; the cases are in include/dem_edem_cases.h):
// edem_ellipsoid3, edem_ellipsoid_cts and edem_ellipsoid_discts (radii up to
// (1, 2, 4)) with their populations: Var(normalized face density) <= 0.014,
// 0 fold-overs, on the ellipsoid to 1e-12. Part 1: test_edem_shared.cpp.
// Skipped (77) when the shared data folder is not available.
#include <dem_edem_cases.h>

int main()
{
  using namespace dem_edem_cases;
  if(!data_available("edem_ellipsoid3.off")) {
    std::cout << "shared data not found in '" << data_dir() << "': skipped" << std::endl;
    return skip_code;
  }
  Stopwatch total;
  for(const char* name : {"edem_ellipsoid3", "edem_ellipsoid_cts", "edem_ellipsoid_discts"}) population_case(name);
  std::cout << "total " << total.seconds() << " s" << std::endl;
  return finish("test_edem_elongated_shared");
}
