//! Joint ranges as the finishing stage reads them: a joint value's
//! representatives inside its limits (a rotation joint's angle wrapped into
//! (-pi, pi] and shifted by whole turns), with the inline rounding the hot
//! path uses.

use super::{AnalyticOptions, RangeFilter, Representatives};
use crate::model::{JointKind, Model};

/// Most representatives of one joint angle kept per candidate.
const MAX_REPRESENTATIVES: usize = 8;

/// A joint's range as the finishing stage reads it, with the options,
/// fixed at set-up: which representatives of a value it returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Range {
    /// A sliding joint: the value, kept when within `[lower, upper]`.
    Slide { lower: f64, upper: f64 },
    /// A sliding joint, limits ignored: the value.
    FreeSlide,
    /// A rotation joint without finite limits (or limits ignored): the
    /// representative nearest the current value.
    Nearest,
    /// A rotation joint with one finite limit, or both with
    /// [`Representatives::Nearest`]: the representative inside nearest the
    /// current value, if any.
    NearestInside { lower: f64, upper: f64 },
    /// A rotation joint with both limits finite: every representative inside.
    Every { lower: f64, upper: f64 },
    /// A rotation joint with limits within [-2 pi, 2 pi] spanning less
    /// than 2 pi: at most one representative of an angle in (-pi, pi]
    /// lies inside, among the angle and the angle +- 2 pi.
    Narrow { lower: f64, upper: f64 },
}

impl Range {
    pub(super) fn of(model: &Model, j: usize, options: &AnalyticOptions) -> Range {
        use std::f64::consts::TAU;
        let joint = &model.joints()[j];
        let (lower, upper) = (joint.limits.lower, joint.limits.upper);
        let ignore = options.limits == RangeFilter::IgnoreLimits;
        if joint.kind == JointKind::Prismatic {
            if ignore {
                Range::FreeSlide
            } else {
                Range::Slide { lower, upper }
            }
        } else if ignore || (lower == f64::NEG_INFINITY && upper == f64::INFINITY) {
            Range::Nearest
        } else if !joint.limits.is_bounded() {
            Range::NearestInside { lower, upper }
        } else if upper - lower < TAU && lower >= -TAU && upper <= TAU {
            Range::Narrow { lower, upper }
        } else if options.representatives == Representatives::Nearest {
            Range::NearestInside { lower, upper }
        } else {
            Range::Every { lower, upper }
        }
    }

    pub(super) fn is_rotation(&self) -> bool {
        !matches!(self, Range::Slide { .. } | Range::FreeSlide)
    }
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Choices {
    /// The value as the range reads it (an angle wrapped into (-pi, pi]).
    pub(super) wrapped: f64,
    /// The first representative, `wrapped + 2 pi k`.
    pub(super) first: f64,
    /// `k`, an integer (0 for slides).
    pub(super) k: f64,
    /// How many: `wrapped + 2 pi (k + i)` for `i` below it.
    pub(super) count: usize,
}

/// The representatives of a joint with `range` to return for `value` (as
/// solved: a rotation joint's angle is first wrapped into (-pi, pi]),
/// given the joint's `current` value. Inline: it runs for every joint of
/// every candidate (the rarer cases are out of line).
#[inline(always)]
pub(super) fn representatives(range: Range, value: f64, current: f64) -> Choices {
    use std::f64::consts::TAU;
    let one = |wrapped: f64, k: f64, first: f64, inside: bool| Choices {
        wrapped,
        first,
        k,
        count: usize::from(inside),
    };
    match range {
        Range::Narrow { lower, upper } => {
            // The only representative inside, if any.
            let w = wrap(value);
            if w < lower {
                let v = w + TAU;
                one(w, 1.0, v, v >= lower && v <= upper)
            } else if w > upper {
                let v = w - TAU;
                one(w, -1.0, v, v >= lower && v <= upper)
            } else {
                one(w, 0.0, w, true)
            }
        }
        Range::Slide { lower, upper } => one(value, 0.0, value, value >= lower && value <= upper),
        Range::FreeSlide => one(value, 0.0, value, true),
        Range::Nearest => {
            let w = wrap(value);
            let k = nearest_turns(w, current);
            one(w, k, w + TAU * k, true)
        }
        Range::NearestInside { lower, upper } => {
            // The one nearest the current value if inside, else (out of
            // line) the one just inside the bound it passed.
            let w = wrap(value);
            let k = nearest_turns(w, current);
            let v = w + TAU * k;
            if v >= lower && v <= upper {
                one(w, k, v, true)
            } else {
                inside_bound(w, v, lower, upper)
            }
        }
        Range::Every { lower, upper } => every(wrap(value), lower, upper),
    }
}

/// The multiple of 2 pi taking `wrapped` nearest `current` (0 without a
/// rounding when they are within pi).
#[inline(always)]
fn nearest_turns(wrapped: f64, current: f64) -> f64 {
    let gap = current - wrapped;
    if gap.abs() < std::f64::consts::PI {
        0.0
    } else {
        nearest_integer(gap * (1.0 / std::f64::consts::TAU))
    }
}

/// [`Range::NearestInside`] when the representative `v` nearest the
/// current value is outside `[lower, upper]`: the one just inside the
/// bound it passed, if it is inside the other.
#[inline(never)]
fn inside_bound(w: f64, v: f64, lower: f64, upper: f64) -> Choices {
    use std::f64::consts::TAU;
    let k = if v < lower {
        ceil((lower - w) / TAU)
    } else {
        floor((upper - w) / TAU)
    };
    let v = w + TAU * k;
    Choices {
        wrapped: w,
        first: v,
        k,
        count: usize::from(v >= lower && v <= upper),
    }
}

/// [`Range::Every`]: every representative of `w` in `[lower, upper]`.
#[inline(always)]
fn every(w: f64, lower: f64, upper: f64) -> Choices {
    use std::f64::consts::TAU;
    let first = ceil((lower - w) / TAU);
    let last = floor((upper - w) / TAU);
    let count = if last >= first {
        ((last - first) as usize).saturating_add(1)
    } else {
        0
    };
    Choices {
        wrapped: w,
        first: w + TAU * first,
        k: first,
        count: count.min(MAX_REPRESENTATIVES),
    }
}

/// Largest magnitude below which [`nearest_integer`], [`floor`] and
/// [`ceil`] round by adding and subtracting `1.5 * 2^52` (exact there:
/// the sum's unit in the last place is 1) instead of the library call.
const FAST_INTEGER_LIMIT: f64 = 2_251_799_813_685_248.0; // 2^51

/// The integer nearest `x` (halves to even), inline for moderate `x`.
#[inline]
fn nearest_integer(x: f64) -> f64 {
    const SHIFT: f64 = 6_755_399_441_055_744.0; // 1.5 * 2^52
    if x.abs() < FAST_INTEGER_LIMIT {
        (x + SHIFT) - SHIFT
    } else {
        x.round_ties_even()
    }
}

/// `x.floor()`, inline for moderate `x` (the library call costs more than
/// the rest of a representative).
#[inline]
fn floor(x: f64) -> f64 {
    let r = nearest_integer(x);
    if r > x {
        r - 1.0
    } else {
        r
    }
}

/// `x.ceil()`, inline for moderate `x`.
#[inline]
fn ceil(x: f64) -> f64 {
    -floor(-x)
}

/// `angle` wrapped into (-pi, pi] (one addition for the angles the
/// subproblems produce, which lie within a few turns).
#[inline]
fn wrap(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let shifted = if angle > PI {
        angle - TAU
    } else if angle <= -PI {
        angle + TAU
    } else {
        return angle;
    };
    if shifted > -PI && shifted <= PI {
        shifted
    } else {
        crate::math::wrap_angle(angle)
    }
}

/// Upper bound on the representatives of an angle within `[lower, upper]`.
pub(super) fn representatives_bound(lower: f64, upper: f64) -> usize {
    if lower.is_finite() && upper.is_finite() {
        let span = ((upper - lower) / std::f64::consts::TAU).floor();
        (span as usize + 1).clamp(1, MAX_REPRESENTATIVES)
    } else {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inline_rounding_matches_the_library() {
        let values = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.49999999999999994,
            -2.3,
            7.9,
            -7.9,
            1e15,
            -1e15,
            3.9e15,
            5e15,
            -5e15,
            1e300,
            4503599627370495.5,
            2251799813685247.5,
            -2251799813685247.5,
            2251799813685248.5,
            -2251799813685249.5,
            3.5,
            -2.5,
            f64::INFINITY,
        ];
        for x in values {
            assert_eq!(floor(x), x.floor(), "floor {x}");
            assert_eq!(ceil(x), x.ceil(), "ceil {x}");
            assert_eq!(nearest_integer(x), x.round_ties_even(), "nearest {x}");
        }
    }

    #[test]
    fn wrap_matches_wrap_angle() {
        for k in -4000..4000 {
            let x = k as f64 * 0.00377 + 1e-3;
            let w = wrap(x);
            assert!(w > -std::f64::consts::PI && w <= std::f64::consts::PI);
            assert!((w - crate::math::wrap_angle(x)).abs() < 1e-15, "{x}");
        }
        assert_eq!(wrap(std::f64::consts::PI), std::f64::consts::PI);
    }
}
