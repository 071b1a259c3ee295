% optimoptions for GNU Octave: the options of the reference codes are only
% display settings, which the sqp of octave_shims/fmincon ignores.
function options = optimoptions(varargin)
  options = struct();
end
