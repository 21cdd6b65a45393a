//! The geometry the analytic solvers are assembled from, below them: the
//! arm's joint axes as lines ([`structure`]), the geometric subproblems
//! ([`subproblems`], and [`subproblem6`] on four axes), and the real roots
//! of the degree-2 trigonometric polynomials they reduce to (`trig2`).
//! Nothing here knows a solver or an arm class.

pub mod structure;
pub mod subproblem6;
pub mod subproblems;
pub(crate) mod trig2;
