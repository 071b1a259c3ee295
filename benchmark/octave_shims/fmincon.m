% fmincon for GNU Octave, as far as the reference codes call it (objective,
% start, bounds; no other constraints): Octave's own sqp with the same bounds.
function x = fmincon(objective, x0, A, b, Aeq, beq, lb, ub, nonlcon, options)
  if ~(isempty(A) && isempty(b) && isempty(Aeq) && isempty(beq) && (nargin < 9 || isempty(nonlcon)))
    error('octave_shims/fmincon: only bound constraints are supported');
  end
  x = sqp(x0(:), @(y) objective(y'), [], [], lb(:), ub(:))';
end
