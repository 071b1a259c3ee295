% Times the authors' SDEM (the MATLAB code of Lyu, Lui and Choi,
% https://github.com/garyptchoi/spherical-density-equalizing-map) in GNU Octave
% on a mesh with the area population, as its demo_SDEM.m runs it (FLASH, the
% Moebius area correction, then SDEM with dt 0.1, epsilon 1e-3 and at most
% 200 iterations), for the side-by-side comparison with `dem sdem` of issue 19
% item 3 (benchmark/RESULTS.md, "SDEM against the reference code").
%
% usage (from this directory):
%   octave --no-gui --quiet --eval "reference_sdem('REPO/code', 'MESH.off' [, 'DEM_MAP.off'])"
%
% Prints one line per stage with its wall time, the number of iterations, the
% final std(rho)/mean(rho) of the vertex density (the reference's own measure,
% on the output map) and the number of faces whose image turns over about the
% centre (a floating-point orientation test). With DEM_MAP.off (the output of
% `dem sdem MESH.off --output DEM_MAP.off`), the same two measures of that map.
% Octave has no fmincon or optimoptions: octave_shims/ provides them through
% Octave's own sqp (same bounds, same start), used only when they are missing.
function reference_sdem(code_dir, mesh_file, dem_map_file)
  addpath(code_dir);
  if exist('fmincon') == 0
    addpath(fullfile(fileparts(mfilename('fullpath')), 'octave_shims'));
  end
  [v, f] = read_off_mesh(mesh_file);
  population = triangle_areas(v, f);
  t = tic; S1 = spherical_conformal_map(v, f); t_flash = toc(t);
  t = tic; S = mobius_area_correction_spherical(v, f, S1); t_mobius = toc(t);
  t = tic; output = evalc('map = SDEM(v, f, population, S, 0.1, 1e-3, 200);'); t_sdem = toc(t);
  % SDEM prints a header, then one line per step from step 0
  steps = numel(strfind(output, sprintf('\n'))) - 2;
  printf('%s: %d vertices, %d faces\n', mesh_file, rows(v), rows(f));
  printf('  FLASH %.3f s, Moebius %.3f s, SDEM %.3f s (%d iterations), total %.3f s\n', ...
         t_flash, t_mobius, t_sdem, steps, t_flash + t_mobius + t_sdem);
  print_quality('reference', map, f, population);
  if nargin > 2
    [dem_map, dem_f] = read_off_mesh(dem_map_file);
    if ~isequal(dem_f, f), error('%s does not have the faces of %s', dem_map_file, mesh_file); end
    print_quality('dem', dem_map, f, population);
  end
end

function print_quality(name, map, f, population)
  rho_v = f2v_area(map, f) * (population ./ triangle_areas(map, f));
  a = map(f(:, 1), :); b = map(f(:, 2), :); c = map(f(:, 3), :);
  turned = sum(dot(cross(b - a, c - a, 2), a + b + c, 2) <= 0);
  printf('  %s map: std(rho)/mean(rho) %.4g, turned faces %d\n', name, std(rho_v) / mean(rho_v), turned);
end

function [v, f] = read_off_mesh(file)
  fid = fopen(file, 'r');
  if fid < 0, error('cannot open %s', file); end
  words = {};
  while numel(words) < 4 % the OFF keyword and the three counts, comments skipped
    line = strtrim(fgetl(fid));
    if isempty(line) || line(1) == '#', continue; end
    words = [words, strsplit(line)];
  end
  counts = str2double(words(2:4));
  v = fscanf(fid, '%f', [3, counts(1)])';
  f = fscanf(fid, '%d', [4, counts(2)])';
  fclose(fid);
  if any(f(:, 1) ~= 3), error('%s: only triangles are read', file); end
  f = f(:, 2:4) + 1;
end

function a = triangle_areas(v, f)
  a = 0.5 * sqrt(sum(cross(v(f(:, 2), :) - v(f(:, 1), :), v(f(:, 3), :) - v(f(:, 1), :), 2) .^ 2, 2));
end
