//! Deflection of a simply supported beam under point loads (seed 000, sec 3.1).
//!
//! Euler-Bernoulli beam of length `L`, supported at `x = 0` and `x = L`,
//! bending stiffness `E I`. Deflections are positive downward, in metres.
//!
//! ```
//! use armkit::beam::SimplySupportedBeam;
//! let beam = SimplySupportedBeam::new(10.0, 200e9, 0.2_f64.powi(4) / 12.0).unwrap();
//! // 1 kN at mid-span: P L^3 / (48 E I)
//! let w = beam.deflection_under_load(5.0, 1000.0).unwrap();
//! assert!((w - 1000.0 * 1000.0 / (48.0 * 200e9 * 0.2_f64.powi(4) / 12.0)).abs() < 1e-15);
//! ```

use crate::error::{Error, Result};

/// A simply supported beam: span (m), Young's modulus (Pa), second moment of
/// area of its section (m^4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimplySupportedBeam {
    length: f64,
    youngs_modulus: f64,
    second_moment: f64,
}

impl SimplySupportedBeam {
    /// Checks `length`, `youngs_modulus` and `second_moment` are finite and > 0.
    pub fn new(length: f64, youngs_modulus: f64, second_moment: f64) -> Result<Self> {
        for (name, value) in [
            ("length", length),
            ("youngs_modulus", youngs_modulus),
            ("second_moment", second_moment),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid_argument(
                    name,
                    format!("must be finite and > 0, got {value}"),
                ));
            }
        }
        Ok(SimplySupportedBeam {
            length,
            youngs_modulus,
            second_moment,
        })
    }

    /// Span, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Bending stiffness `E I`, N m^2.
    pub fn stiffness(&self) -> f64 {
        self.youngs_modulus * self.second_moment
    }

    /// Deflection (m, downward) at the point of a single load of `force`
    /// newtons placed at `position` m from the left support:
    /// `w = F a^2 b^2 / (3 E I L)`, `b = L - a` (seed 000, eq 1).
    pub fn deflection_under_load(&self, position: f64, force: f64) -> Result<f64> {
        self.check_position(position)?;
        Ok(self.deflection_and_slope_under_load(position, force).0)
    }

    pub(crate) fn check_position(&self, position: f64) -> Result<()> {
        if !(position.is_finite() && (0.0..=self.length).contains(&position)) {
            return Err(Error::invalid_argument(
                "position",
                format!(
                    "must lie on the span [0, {}] m, got {position}",
                    self.length
                ),
            ));
        }
        Ok(())
    }

    /// `(w, dw/da)` for a load at `a`, clamped to the span (the derivative is
    /// zero outside it). Corrected seed 000 eq 8:
    /// `d/da [a^2 (L-a)^2] = 2 a (L-a)(L-2a)`.
    fn deflection_and_slope_under_load(&self, a: f64, force: f64) -> (f64, f64) {
        let l = self.length;
        if !(0.0..=l).contains(&a) {
            let clamped = a.clamp(0.0, l);
            return (self.deflection_and_slope_under_load(clamped, force).0, 0.0);
        }
        let b = l - a;
        let k = force / (3.0 * self.stiffness() * l);
        (k * a * a * b * b, k * 2.0 * a * b * (l - 2.0 * a))
    }
}

/// A carriage of weight `force` (N) riding on a beam: the deflection under it
/// as a function of its position (the gantry's `w(d2)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarriageDeflection {
    /// The beam.
    pub beam: SimplySupportedBeam,
    /// The carriage's weight (arm and payload), N, downward positive.
    pub force: f64,
}

impl CarriageDeflection {
    /// `(w, dw/da)` in m and m/m for the carriage at `a` m from the left
    /// support; positions off the span are clamped to it (slope zero there).
    pub fn deflection_and_slope(&self, a: f64) -> (f64, f64) {
        self.beam.deflection_and_slope_under_load(a, self.force)
    }
}
