//! The geometric subproblems the analytic solvers are assembled from
//! (Paden and Kahan's subproblems 1-3, and subproblem 4 of Elias and Wen's
//! IK-Geo numbering), derived here from the geometry of a point rotating
//! about an axis.
//!
//! Notation: `R(k, t)` is the rotation by `t` rad about the unit axis `k`
//! through the origin (Rodrigues: `R p = p_par + cos t p_perp + sin t k x p`
//! with `p_par = (k.p) k`, `p_perp = p - p_par`). Every subproblem returns
//! every solution it has, with a flag saying whether they are exact or the
//! least-squares answer of an unsolvable instance (a point out of reach):
//!
//! | # | unknowns | equation | solutions |
//! |---|---|---|---|
//! | 1 | t | `R(k, t) p1 = p2` | 1 |
//! | 2 | t1, t2 | `R(k1, t1) p1 = R(k2, t2) p2` | 1 or 2 |
//! | 3 | t | `|R(k, t) p1 - p2| = d` | 1 or 2 |
//! | 4 | t | `h . R(k, t) p = d` | 1 or 2 |
//!
//! Nothing allocates; solutions come in a fixed-size [`Angles`].
//!
//! ```
//! use armkit::ik::analytic::subproblems::{rotation, subproblem1};
//! use armkit::math::Vector3;
//! let k = Vector3::z();
//! let p1 = Vector3::new(1.0, 0.0, 0.5);
//! let p2 = rotation(&k, 0.7) * p1;
//! let (t, exact) = subproblem1(&k, &p1, &p2);
//! assert!(exact && (t - 0.7).abs() < 1e-14);
//! ```

use crate::math::{sin_cos, Matrix3, Vector3};

/// Relative size below which a residual counts as round-off when a
/// subproblem decides between "exact" and "least squares": `1e-9` of the
/// lengths involved. (The analytic solvers decide a solution's fit by
/// forward kinematics in the end; this flag is only the subproblem's own
/// view.)
pub(crate) const RELATIVE_TOLERANCE: f64 = 1e-9;

/// Up to `N` solutions of a subproblem with a flag: exact solutions, or
/// the least-squares answer of an instance without exact solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solutions<T, const N: usize> {
    items: [T; N],
    count: usize,
    /// True when the solutions solve the equations exactly (to round-off).
    pub exact: bool,
}

impl<T: Copy, const N: usize> Solutions<T, N> {
    pub(crate) fn new(items: [T; N], count: usize, exact: bool) -> Self {
        Solutions {
            items,
            count,
            exact,
        }
    }

    /// The solutions (at most `N`).
    pub fn as_slice(&self) -> &[T] {
        &self.items[..self.count]
    }

    /// Each solution mapped by `f`, with the same flag.
    pub(crate) fn map<U: Copy>(&self, f: impl FnMut(T) -> U) -> Solutions<U, N> {
        Solutions::new(self.items.map(f), self.count, self.exact)
    }
}

/// Up to two angles (rad), for subproblems 3 and 4.
pub type Angles = Solutions<f64, 2>;

/// Up to two angle pairs `(t1, t2)` (rad), for subproblem 2.
pub type AnglePairs = Solutions<(f64, f64), 2>;

/// Up to two [`Turn`]s, as [`Angles`].
pub(crate) type Turns = Solutions<Turn, 2>;

/// Up to two pairs of [`Turn`]s, as [`AnglePairs`].
pub(crate) type TurnPairs = Solutions<(Turn, Turn), 2>;

/// The rotation matrix `R(k, t)` about the unit axis `k` by `t` rad (Rodrigues).
pub fn rotation(k: &Vector3<f64>, t: f64) -> Matrix3<f64> {
    let (s, c) = sin_cos(t);
    rotation_sc(k, s, c)
}

/// `R(k, t)` from `sin t` and `cos t`.
#[inline]
fn rotation_sc(k: &Vector3<f64>, s: f64, c: f64) -> Matrix3<f64> {
    let v = 1.0 - c;
    let (x, y, z) = (k.x, k.y, k.z);
    Matrix3::new(
        c + x * x * v,
        x * y * v - z * s,
        x * z * v + y * s,
        y * x * v + z * s,
        c + y * y * v,
        y * z * v - x * s,
        z * x * v - y * s,
        z * y * v + x * s,
        c + z * z * v,
    )
}

/// Subproblem 1: the angle `t` (rad) that turns `p1` about the unit axis `k`
/// onto `p2`, `R(k, t) p1 = p2`; when no angle does (different heights along
/// `k` or different distances from it), the one minimizing `|R(k, t) p1 - p2|`
/// (the projections onto the plane normal to `k` aligned). Returns the angle
/// and whether it is exact (to 1e-9 of the lengths involved). If either projection
/// is zero every angle is as good and 0 is returned.
pub fn subproblem1(k: &Vector3<f64>, p1: &Vector3<f64>, p2: &Vector3<f64>) -> (f64, bool) {
    let (y, x, exact) = subproblem1_direction(k, p1, p2);
    (atan2(y, x), exact)
}

/// Subproblem 1's angle as a direction `(y, x)` (the angle is
/// `atan2(y, x)`) and whether it is exact.
#[inline]
fn subproblem1_direction(
    k: &Vector3<f64>,
    p1: &Vector3<f64>,
    p2: &Vector3<f64>,
) -> (f64, f64, bool) {
    let kp1 = k.dot(p1);
    let kp2 = k.dot(p2);
    let x = p1.dot(p2) - kp1 * kp2;
    let y = k.dot(&p1.cross(p2));
    let (length1, length2) = (p1.norm_squared(), p2.norm_squared());
    let n1 = (length1 - kp1 * kp1).max(0.0).sqrt();
    let n2 = (length2 - kp2 * kp2).max(0.0).sqrt();
    (y, x, same_circle(kp1, n1, kp2, n2, length1.max(length2)))
}

/// Subproblem 1's exactness test: equal heights along the axis and equal
/// distances from it, to the relative tolerance of the larger length
/// (`scale2` its square).
#[inline]
pub(crate) fn same_circle(
    height1: f64,
    radius1: f64,
    height2: f64,
    radius2: f64,
    scale2: f64,
) -> bool {
    let tolerance = RELATIVE_TOLERANCE * scale2.sqrt().max(f64::MIN_POSITIVE);
    (height1 - height2).abs() <= tolerance && (radius1 - radius2).abs() <= tolerance
}

/// Subproblem 4: the angles `t` (rad) with `h . R(k, t) p = d` (`k` a unit
/// axis; `h` any vector). Expanding Rodrigues, `A cos t + B sin t = c` with
/// `A = h . p_perp`, `B = h . (k x p)`, `c = d - (h . k)(k . p)`: two
/// solutions `atan2(B, A) +- acos(c / r)`, `r = hypot(A, B)`, when
/// `|c| <= r`; otherwise the one angle that brings `h . R p` nearest `d`
/// (least squares). Degenerate `r = 0` (the left side does not depend on
/// `t`): angle 0, exact only if `c = 0`.
pub fn subproblem4(h: &Vector3<f64>, k: &Vector3<f64>, p: &Vector3<f64>, d: f64) -> Angles {
    Sinusoid::new(h, k, p).solve(d).map(|t| t.angle)
}

/// Subproblem 3: the angles `t` (rad) with `|R(k, t) p1 - p2| = d` (`k` a
/// unit axis, `d >= 0`): squared, `p2 . R(k, t) p1 = (|p1|^2 + |p2|^2 - d^2)
/// / 2`, a subproblem 4. When no angle reaches `d` the least-squares answer
/// is the angle whose distance comes nearest.
pub fn subproblem3(k: &Vector3<f64>, p1: &Vector3<f64>, p2: &Vector3<f64>, d: f64) -> Angles {
    Distance::new(k, p1, p2).solve(d).map(|t| t.angle)
}

/// `atan2(y, x)` (rad, in `[-pi, pi]`) to about one unit in the last place,
/// in a fraction of the platform routine's instructions (the subproblems
/// take several per solve). `|y|` and `|x|` give `a = min / max` in
/// `[0, 1]`; with `c = k / 32` the 32nd at or just below it (a table
/// index, found without a branch), `atan(a) = atan(c) + atan(t)`,
/// `t = (a - c) / (1 + c a)` in `[0, 1/32]` (to a rounding below 0: no
/// cancellation against `atan(c)`), and `atan(t)`
/// by its Taylor series to `t^11` (the first omitted term is below
/// `2^-60 t`); `atan(c)` is tabulated as a head and a tail (from 200-bit
/// values); then the octant, the half plane and the sign of `y`. `(0, 0)`
/// gives 0; non-finite input goes to the platform routine.
#[allow(clippy::excessive_precision)]
#[inline]
pub(crate) fn atan2(y: f64, x: f64) -> f64 {
    /// `atan(k / 32)` for `k = 0..=32`, head and tail.
    const ATAN_THIRTY_SECONDS: [(f64, f64); 33] = [
        (0.0, 0.0),
        (0.031239833430268277, -1.188442711587748e-18),
        (0.06241880999595735, -1.5490756308295046e-18),
        (0.09347678115858947, -6.2844725995420954e-18),
        (0.12435499454676144, -3.1253241424539383e-18),
        (0.15499674192394097, 9.585415594114324e-18),
        (0.18534794999569476, 4.180692268843079e-18),
        (0.21535769969773805, 4.738160130078733e-19),
        (0.24497866312686414, 1.0698755618734451e-17),
        (0.2741674511196588, 8.261353575163773e-18),
        (0.3028848683749714, -1.1010827903001369e-17),
        (0.3310960767041321, -7.952610375793799e-18),
        (0.35877067027057225, -2.4623815582638635e-17),
        (0.38588266939807375, 2.378822732491941e-17),
        (0.4124104415973873, -1.587652227770689e-17),
        (0.43833655985795783, -2.494277030626541e-17),
        (0.4636476090008061, 2.2698777452961687e-17),
        (0.48833395105640554, -1.1373236189329585e-17),
        (0.5123894603107377, -2.5462781472855804e-17),
        (0.5358112379604637, -4.0637956834825575e-18),
        (0.5585993153435624, -5.4556305485916264e-18),
        (0.5807563535676704, -1.441464378193067e-17),
        (0.6022873461349642, 2.950430737228402e-17),
        (0.6231993299340659, 2.672403885140095e-17),
        (0.6435011087932844, 1.5834785051444286e-17),
        (0.6632029927060933, -3.076054864429649e-17),
        (0.6823165548747481, 6.943223671560008e-18),
        (0.7008544078844502, -1.987626234335816e-17),
        (0.7188299996216245, -2.1478388444456983e-17),
        (0.7362574289814281, 3.473937648299457e-17),
        (0.7531512809621944, -2.4256934659182068e-17),
        (0.7695264804056583, -3.704991905602721e-17),
        (std::f64::consts::FRAC_PI_4, 3.061616997868383e-17),
    ];
    /// `(-1)^n / (2 n + 1)` for `n = 1..=5`.
    const TAYLOR: [f64; 5] = [-1.0 / 3.0, 1.0 / 5.0, -1.0 / 7.0, 1.0 / 9.0, -1.0 / 11.0];
    const HALF_PI: (f64, f64) = (
        std::f64::consts::FRAC_PI_2,
        6.123_233_995_736_766_035_87e-17,
    );
    const PI: (f64, f64) = (std::f64::consts::PI, 1.224_646_799_147_353_207_17e-16);
    let (ax, ay) = (x.abs(), y.abs());
    if !(ax <= f64::MAX && ay <= f64::MAX) {
        return y.atan2(x);
    }
    let (small, large) = if ay > ax { (ax, ay) } else { (ay, ax) };
    if large == 0.0 {
        return 0.0;
    }
    let a = small / large;
    // k = floor(32 a) in 0..=32 by rounding 32 a - 1/2 to an integer with
    // the 1.5 * 2^52 shift (whose low mantissa bits are then k). A tie
    // (32 a an integer, or 32 a - 1/2 rounded onto a half) may give one
    // less or one more; then t is at most 1/32, or a rounding below 0.
    // The `min` only spares a bounds check.
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let shifted = (a * 32.0 - 0.5) + SHIFT;
    let c = (shifted - SHIFT) * 0.03125;
    let k = ((shifted.to_bits() & 63) as usize).min(32);
    let (head, tail) = ATAN_THIRTY_SECONDS[k];
    // a - c is exact (Sterbenz: c / 2 <= a <= 2 c for k >= 1).
    let t = (a - c) / (1.0 + c * a);
    let z = t * t;
    let p = z * (TAYLOR[0] + z * (TAYLOR[1] + z * (TAYLOR[2] + z * (TAYLOR[3] + z * TAYLOR[4]))));
    let mut angle = head + (t + (t * p + tail));
    if ay > ax {
        angle = (HALF_PI.0 - angle) + HALF_PI.1;
    }
    if x < 0.0 {
        angle = (PI.0 - angle) + PI.1;
    }
    angle.copysign(y)
}

/// An angle (rad) with its sine and cosine, so that the rotation by it is
/// built without trigonometry ([`rotation_of`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Turn {
    /// The angle, rad.
    pub angle: f64,
    /// Its sine.
    pub sin: f64,
    /// Its cosine.
    pub cos: f64,
}

impl Turn {
    /// The turn by `angle` rad (one sine-cosine evaluation).
    #[inline]
    pub(crate) fn of_angle(angle: f64) -> Turn {
        let (sin, cos) = sin_cos(angle);
        Turn { angle, sin, cos }
    }

    /// The zero turn.
    pub(crate) const ZERO: Turn = Turn {
        angle: 0.0,
        sin: 0.0,
        cos: 1.0,
    };

    /// The turn of the direction `(x, y)` (`atan2(y, x)`; zero for `(0, 0)`).
    #[inline]
    pub(crate) fn of_direction(y: f64, x: f64) -> Turn {
        // Lengths here are products of arm dimensions: no overflow, so no
        // need for `hypot`'s slower scaling.
        let length = (x * x + y * y).sqrt();
        if length > 0.0 {
            let inverse = 1.0 / length;
            Turn {
                angle: atan2(y, x),
                sin: y * inverse,
                cos: x * inverse,
            }
        } else {
            Turn::ZERO
        }
    }

    /// The turn by `self.angle + other.angle` (sine and cosine by the
    /// addition formulas, no trigonometry).
    #[inline]
    pub(crate) fn plus(&self, other: &Turn) -> Turn {
        Turn {
            angle: self.angle + other.angle,
            sin: self.sin * other.cos + self.cos * other.sin,
            cos: self.cos * other.cos - self.sin * other.sin,
        }
    }

    /// The turn by `sign * angle` for `sign = +-1`.
    #[inline]
    pub(crate) fn times_sign(&self, sign: f64) -> Turn {
        Turn {
            angle: sign * self.angle,
            sin: sign * self.sin,
            cos: self.cos,
        }
    }

    /// `R(k, t)' v = R(k, -t) v` ([`rotate_by`] with the sine negated).
    #[inline]
    pub(crate) fn rotate_back(&self, k: &Vector3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
        rotate_by(k, v, -self.sin, self.cos)
    }
}

/// `R(k, t) v` for the turn of sine `s` and cosine `c` about the unit axis
/// `k` (Rodrigues, no matrix): `c v + s k x v + (1 - c)(k . v) k`.
#[inline]
pub(crate) fn rotate_by(k: &Vector3<f64>, v: &Vector3<f64>, s: f64, c: f64) -> Vector3<f64> {
    v * c + k.cross(v) * s + k * ((1.0 - c) * k.dot(v))
}

/// Subproblem 4 with `h`, `k`, `p` fixed (read once, at set-up), for many
/// right-hand sides `d`: `A cos t + B sin t = d - (h . k)(k . p)` (see
/// [`subproblem4`]). The solutions' sines and cosines come from `A`, `B`
/// and `c / r` by algebra, without trigonometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sinusoid {
    /// `atan2(B, A)` and its cosine and sine (`A / r`, `B / r`).
    phi: Turn,
    /// `hypot(A, B)`.
    r: f64,
    /// `(h . k)(k . p)`.
    offset: f64,
    /// `|h| |p|`, the scale of the tolerances.
    size: f64,
}

impl Sinusoid {
    /// The sinusoid of `h . R(k, t) p`.
    #[inline]
    pub(crate) fn new(h: &Vector3<f64>, k: &Vector3<f64>, p: &Vector3<f64>) -> Sinusoid {
        let kp = k.dot(p);
        let hk = h.dot(k);
        let a = h.dot(p) - hk * kp;
        let b = h.dot(&k.cross(p));
        Sinusoid::of_coefficients(a, b, hk * kp, h.norm() * p.norm())
    }

    /// The sinusoid `a cos t + b sin t + offset` (`size` the scale of its
    /// tolerances).
    #[inline]
    fn of_coefficients(a: f64, b: f64, offset: f64, size: f64) -> Sinusoid {
        let r = (a * a + b * b).sqrt();
        let phi = if r > 0.0 {
            Turn {
                angle: atan2(b, a),
                sin: b / r,
                cos: a / r,
            }
        } else {
            Turn::ZERO
        };
        Sinusoid {
            phi,
            r,
            offset,
            size,
        }
    }

    /// The angles with `h . R(k, t) p = d` (see [`subproblem4`]).
    #[inline(always)]
    pub(crate) fn solve(&self, d: f64) -> Turns {
        let c = d - self.offset;
        let scale = self.size.max(d.abs()).max(f64::MIN_POSITIVE);
        let one = |turn: Turn, exact: bool| Turns::new([turn, turn], 1, exact);
        if self.r <= RELATIVE_TOLERANCE * scale * 1e-3 {
            return one(Turn::ZERO, c.abs() <= RELATIVE_TOLERANCE * scale);
        }
        let phi = self.phi;
        let ratio = c / self.r;
        if ratio.abs() > 1.0 {
            // No exact solution: cos(t - phi) = +-1 comes nearest.
            let exact = (c.abs() - self.r) <= RELATIVE_TOLERANCE * scale;
            let turn = if ratio > 0.0 {
                phi
            } else {
                Turn {
                    angle: phi.angle + std::f64::consts::PI,
                    sin: -phi.sin,
                    cos: -phi.cos,
                }
            };
            return one(turn, exact);
        }
        // t = phi +- spread with cos(spread) = ratio; (1 - ratio)(1 + ratio)
        // keeps sin(spread) accurate near ratio = +-1.
        let sine = ((1.0 - ratio) * (1.0 + ratio)).sqrt();
        // acos(ratio), accurate near +-1 too.
        let spread = atan2(sine, ratio);
        let turn = |sign: f64| Turn {
            angle: phi.angle + sign * spread,
            sin: phi.sin * ratio + sign * phi.cos * sine,
            cos: phi.cos * ratio - sign * phi.sin * sine,
        };
        Turns::new([turn(1.0), turn(-1.0)], 2, true)
    }
}

/// The sinusoids of `h . R(k, t) p` with `h` and `k` fixed (read once), for
/// many `p`: `A = (h - (h . k) k) . p`, `B = (h x k) . p`, offset
/// `(h . k)(k . p)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SinusoidFamily {
    k: Vector3<f64>,
    h_perp: Vector3<f64>,
    h_cross_k: Vector3<f64>,
    hk: f64,
    h_norm: f64,
}

impl SinusoidFamily {
    pub(crate) fn new(h: &Vector3<f64>, k: &Vector3<f64>) -> SinusoidFamily {
        let hk = h.dot(k);
        SinusoidFamily {
            k: *k,
            h_perp: h - k * hk,
            h_cross_k: h.cross(k),
            hk,
            h_norm: h.norm(),
        }
    }

    /// The sinusoid of `h . R(k, t) p` (as [`Sinusoid::new`]).
    #[inline]
    pub(crate) fn of(&self, p: &Vector3<f64>) -> Sinusoid {
        Sinusoid::of_coefficients(
            self.h_perp.dot(p),
            self.h_cross_k.dot(p),
            self.hk * self.k.dot(p),
            self.h_norm * p.norm(),
        )
    }
}

/// Subproblem 3 with `k`, `p1`, `p2` fixed, for many distances `d`
/// (see [`subproblem3`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Distance {
    sinusoid: Sinusoid,
    /// `(|p1|^2 + |p2|^2) / 2`.
    half_sum: f64,
}

impl Distance {
    /// The distance `|R(k, t) p1 - p2|` as a function of `t`.
    #[inline]
    pub(crate) fn new(k: &Vector3<f64>, p1: &Vector3<f64>, p2: &Vector3<f64>) -> Distance {
        Distance {
            sinusoid: Sinusoid::new(p2, k, p1),
            half_sum: 0.5 * (p1.norm_squared() + p2.norm_squared()),
        }
    }

    /// The angles with `|R(k, t) p1 - p2| = d`.
    #[inline]
    pub(crate) fn solve(&self, d: f64) -> Turns {
        self.sinusoid.solve(self.half_sum - 0.5 * d * d)
    }
}

/// A unit vector normal to the unit vector `k`.
pub(crate) fn any_normal(k: &Vector3<f64>) -> Vector3<f64> {
    let seed = if k.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    k.cross(&seed).normalize()
}

/// A fixed vector `p` ready to be turned about a fixed unit axis `k`
/// (Rodrigues, split once): `R(k, t) p = par + cos t perp + sin t (k x p)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Spoke {
    par: Vector3<f64>,
    perp: Vector3<f64>,
    cross: Vector3<f64>,
}

impl Spoke {
    pub(crate) fn new(k: &Vector3<f64>, p: &Vector3<f64>) -> Spoke {
        let par = k * k.dot(p);
        Spoke {
            par,
            perp: p - par,
            cross: k.cross(p),
        }
    }

    /// The parts `(par, perp, cross)`: `R(k, t) p = par + cos t perp + sin t cross`.
    #[inline]
    pub(crate) fn parts(&self) -> [Vector3<f64>; 3] {
        [self.par, self.perp, self.cross]
    }

    /// `R(k, t) p`.
    #[inline]
    pub(crate) fn turned(&self, t: &Turn) -> Vector3<f64> {
        self.par + self.perp * t.cos + self.cross * t.sin
    }

    /// `R(k, t)' p = R(k, -t) p`.
    #[inline]
    pub(crate) fn turned_back(&self, t: &Turn) -> Vector3<f64> {
        self.par + self.perp * t.cos - self.cross * t.sin
    }
}

/// Subproblem 1 as a [`Turn`] (see [`subproblem1`]).
#[inline(always)]
pub(crate) fn subproblem1_turn(
    k: &Vector3<f64>,
    p1: &Vector3<f64>,
    p2: &Vector3<f64>,
) -> (Turn, bool) {
    let (y, x, exact) = subproblem1_direction(k, p1, p2);
    (Turn::of_direction(y, x), exact)
}

/// The rotation matrix `R(k, t)` from the turn's sine and cosine (Rodrigues).
#[inline]
pub(crate) fn rotation_of(k: &Vector3<f64>, turn: &Turn) -> Matrix3<f64> {
    rotation_sc(k, turn.sin, turn.cos)
}

/// Subproblem 2: the angle pairs `(t1, t2)` (rad) with
/// `R(k1, t1) p1 = R(k2, t2) p2` (`k1`, `k2` unit axes, not parallel).
///
/// The common point `x` lies on both circles: `k1 . x = k1 . p1`,
/// `k2 . x = k2 . p2`, `|x| = |p1|`. Writing `x = a k1 + b k2 + c k1 x k2`,
/// the first two fix `a` and `b` (a 2 x 2 system with determinant
/// `1 - (k1 . k2)^2`), the sphere fixes `c` up to its sign; each `x` then
/// gives `t1` and `t2` by subproblem 1. When the circles do not meet
/// (negative `c^2`, or `|p1| != |p2|`), `c = 0` and the radius is the mean of
/// `|p1|` and `|p2|`: one least-squares pair. Parallel axes return an empty,
/// inexact answer (the solvers never ask for it).
pub fn subproblem2(
    k1: &Vector3<f64>,
    p1: &Vector3<f64>,
    k2: &Vector3<f64>,
    p2: &Vector3<f64>,
) -> AnglePairs {
    subproblem2_turns(k1, p1, k2, p2).map(|(t1, t2)| (t1.angle, t2.angle))
}

/// Subproblem 2 as [`Turn`]s (see [`subproblem2`]).
pub(crate) fn subproblem2_turns(
    k1: &Vector3<f64>,
    p1: &Vector3<f64>,
    k2: &Vector3<f64>,
    p2: &Vector3<f64>,
) -> TurnPairs {
    let cosine = k1.dot(k2);
    let normal = k1.cross(k2);
    let sine2 = normal.norm_squared();
    if sine2 <= 1e-24 {
        return TurnPairs::new([(Turn::ZERO, Turn::ZERO); 2], 0, false);
    }
    let h1 = k1.dot(p1);
    let h2 = k2.dot(p2);
    let a = (h1 - cosine * h2) / sine2;
    let b = (h2 - cosine * h1) / sine2;
    let base = k1 * a + k2 * b;
    let n1 = p1.norm();
    let n2 = p2.norm();
    let scale = n1.max(n2).max(f64::MIN_POSITIVE);
    let same_radius = (n1 - n2).abs() <= RELATIVE_TOLERANCE * scale;
    let radius2 = n1 * n2;
    let c2 = (radius2 - base.norm_squared()) / sine2;
    let pair = |x: &Vector3<f64>| {
        let (t1, e1) = subproblem1_turn(k1, p1, x);
        let (t2, e2) = subproblem1_turn(k2, p2, x);
        ((t1, t2), e1 && e2)
    };
    if c2 < -RELATIVE_TOLERANCE * scale * scale {
        // The circles do not meet: the point of the plane pair nearest both.
        let x = if base.norm() > 0.0 {
            base * (0.5 * (n1 + n2) / base.norm())
        } else {
            base
        };
        let (values, _) = pair(&x);
        return TurnPairs::new([values, values], 1, false);
    }
    let c = c2.max(0.0).sqrt();
    let (first, e1) = pair(&(base + normal * c));
    let (second, e2) = pair(&(base - normal * c));
    let count = if c == 0.0 { 1 } else { 2 };
    TurnPairs::new([first, second], count, same_radius && e1 && e2)
}

#[cfg(test)]
mod tests;
