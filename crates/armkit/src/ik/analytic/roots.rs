//! Bracketed root refinement shared by the analytic solvers: the Illinois
//! variant of regula falsi (Dowell and Jarratt, 1971), superlinear on a
//! bracket whose ends keep opposite signs.

/// Most Illinois steps per bracket.
pub(crate) const MAX_STEPS: usize = 100;

/// A point of a bracket: `(t, f(t), payload)` (the payload carried from the
/// nearer end to the next trial).
pub(crate) type Point<P> = (f64, f64, P);

/// The Illinois variant of regula falsi: shrinks the bracket `a`, `b`
/// (points `(t, f(t), payload)` with `f(a) f(b) <= 0`) until it is
/// narrower than `width` (or [`MAX_STEPS`] steps); each trial is evaluated
/// by `f(t, payload of the nearer end)`. Returns the final ends (both the
/// trial where `f` is exactly zero); `None` where `f` is undefined.
pub(crate) fn illinois<P: Copy>(
    a: Point<P>,
    b: Point<P>,
    width: f64,
    mut f: impl FnMut(f64, &P) -> Option<(f64, P)>,
) -> Option<(Point<P>, Point<P>)> {
    let (mut a, mut b) = (a, b);
    if a.1 == 0.0 {
        return Some((a, a));
    }
    let mut side = 0i8;
    for _ in 0..MAX_STEPS {
        if (b.0 - a.0).abs() < width {
            break;
        }
        let mut t = (a.0 * b.1 - b.0 * a.1) / (b.1 - a.1);
        if !(t > a.0.min(b.0) && t < a.0.max(b.0)) {
            t = 0.5 * (a.0 + b.0);
        }
        let near = if (t - a.0).abs() <= (t - b.0).abs() {
            &a.2
        } else {
            &b.2
        };
        let (value, payload) = f(t, near)?;
        let point = (t, value, payload);
        if value == 0.0 {
            return Some((point, point));
        }
        if value.signum() == b.1.signum() {
            b = point;
            if side == -1 {
                a.1 *= 0.5;
            }
            side = -1;
        } else {
            a = point;
            if side == 1 {
                b.1 *= 0.5;
            }
            side = 1;
        }
    }
    Some((a, b))
}
