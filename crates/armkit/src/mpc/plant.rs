//! The simulated plant of a closed-loop run: how the joints follow the
//! commanded joint velocities over one sample.
//!
//! [`PlantModel::Exact`] (the default) integrates each command exactly,
//! `q(k+1) = q(k) + T u(k)`. [`PlantModel::LimitedPrecision`] models what
//! seed 000 (sec 5, Example 3) blames for its oscillation, the "lower motion
//! precision" ("较低的运动精度") of the prismatic joints: a drive with a
//! velocity deadband (commands slower than it do not move the axis), a
//! velocity command resolution (the command is rounded to a multiple of it)
//! and a finite position resolution (the axis only stops on, and its encoder
//! only reads, multiples of it from the start; the drive keeps the exact
//! commanded reference internally and the axis follows it to the nearest
//! step). The planner then measures the quantised positions.
//!
//! ```
//! use armkit::model::JointKind;
//! use armkit::mpc::{ActuatorPrecision, Plant, PlantModel};
//! // One prismatic joint with a 1 mm encoder/ball-screw resolution.
//! let model = PlantModel::LimitedPrecision {
//!     prismatic: ActuatorPrecision { position_resolution: 1e-3, ..ActuatorPrecision::EXACT },
//!     rotary: ActuatorPrecision::EXACT,
//! };
//! let mut plant = Plant::new(model, &[JointKind::Prismatic], &[0.0]).unwrap();
//! let mut q = [0.0];
//! plant.advance(&mut q, &[0.004], 0.05).unwrap(); // 0.2 mm commanded: the axis stays put
//! assert_eq!(q[0], 0.0);
//! for _ in 0..2 {
//!     plant.advance(&mut q, &[0.004], 0.05).unwrap(); // 0.6 mm in all: one step
//! }
//! assert!((q[0] - 1e-3).abs() < 1e-15);
//! ```

use crate::error::{check_finite_vector, Error, Result};
use crate::model::JointKind;

/// The precision of one kind of joint actuator. Every field `>= 0`, finite;
/// 0 means "exact" for that effect.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActuatorPrecision {
    /// Position resolution, m (prismatic) or rad (rotary): the axis rests
    /// only on multiples of it from its start position (an encoder count, a
    /// stepper or ball-screw step). 0: continuous.
    pub position_resolution: f64,
    /// Velocity deadband, m/s or rad/s: a commanded speed `|u|` below it
    /// does not move the axis (static friction, the drive's dead zone).
    /// 0: none.
    pub deadband: f64,
    /// Velocity command resolution, m/s or rad/s: the command is rounded to
    /// the nearest multiple of it (a drive's speed quantisation). 0: exact.
    pub velocity_resolution: f64,
}

impl ActuatorPrecision {
    /// An exact actuator: every field 0.
    pub const EXACT: ActuatorPrecision = ActuatorPrecision {
        position_resolution: 0.0,
        deadband: 0.0,
        velocity_resolution: 0.0,
    };

    /// Checks every field is finite and `>= 0`; `what` names the actuator.
    pub fn validate(&self, what: &str) -> Result<()> {
        for (field, value) in [
            ("position_resolution", self.position_resolution),
            ("deadband", self.deadband),
            ("velocity_resolution", self.velocity_resolution),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::invalid_argument(
                    format!("{what}.{field}"),
                    format!("must be finite and >= 0, got {value}"),
                ));
            }
        }
        Ok(())
    }

    /// True when every field is 0.
    pub fn is_exact(&self) -> bool {
        *self == ActuatorPrecision::EXACT
    }

    /// The velocity the axis actually runs at for command `u` (m/s or
    /// rad/s): rounded to the velocity resolution, zero inside the deadband.
    pub fn realised_velocity(&self, u: f64) -> f64 {
        let u = if self.velocity_resolution > 0.0 {
            (u / self.velocity_resolution).round() * self.velocity_resolution
        } else {
            u
        };
        if u.abs() < self.deadband {
            0.0
        } else {
            u
        }
    }

    /// The axis position for the drive's exact reference `reference`, from
    /// `origin` (where the encoder counts from): the nearest step.
    pub fn realised_position(&self, origin: f64, reference: f64) -> f64 {
        if self.position_resolution > 0.0 {
            origin
                + ((reference - origin) / self.position_resolution).round()
                    * self.position_resolution
        } else {
            reference
        }
    }
}

impl Default for ActuatorPrecision {
    /// [`ActuatorPrecision::EXACT`].
    fn default() -> Self {
        ActuatorPrecision::EXACT
    }
}

/// How the simulated joints follow the commands.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PlantModel {
    /// `q(k+1) = q(k) + T u(k)`, exactly (the default).
    #[default]
    Exact,
    /// Actuators of limited precision, one setting for the prismatic joints
    /// and one for the rotary joints.
    LimitedPrecision {
        /// The prismatic joints' actuators.
        prismatic: ActuatorPrecision,
        /// The rotary joints' actuators.
        rotary: ActuatorPrecision,
    },
}

impl PlantModel {
    /// Checks the precisions (see [`ActuatorPrecision::validate`]).
    pub fn validate(&self) -> Result<()> {
        match self {
            PlantModel::Exact => Ok(()),
            PlantModel::LimitedPrecision { prismatic, rotary } => {
                prismatic.validate("plant.prismatic")?;
                rotary.validate("plant.rotary")
            }
        }
    }

    /// The plant of the given actuators: [`PlantModel::Exact`] when both are
    /// exact, else [`PlantModel::LimitedPrecision`]. Errors: a field not
    /// finite or negative (named, e.g. `plant.prismatic.deadband`).
    pub fn of_actuators(
        prismatic: ActuatorPrecision,
        rotary: ActuatorPrecision,
    ) -> Result<PlantModel> {
        let model = if prismatic.is_exact() && rotary.is_exact() {
            PlantModel::Exact
        } else {
            PlantModel::LimitedPrecision { prismatic, rotary }
        };
        model.validate()?;
        Ok(model)
    }

    /// The prismatic joints' position resolution, m (0: continuous, and
    /// for [`PlantModel::Exact`]).
    pub fn prismatic_position_resolution(&self) -> f64 {
        match self {
            PlantModel::Exact => 0.0,
            PlantModel::LimitedPrecision { prismatic, .. } => prismatic.position_resolution,
        }
    }

    /// The precision of a joint of kind `kind` (`None`: exact).
    fn precision(&self, kind: JointKind) -> Option<ActuatorPrecision> {
        match self {
            PlantModel::Exact => None,
            PlantModel::LimitedPrecision { prismatic, rotary } => {
                let p = if kind.is_rotational() {
                    rotary
                } else {
                    prismatic
                };
                (!p.is_exact()).then_some(*p)
            }
        }
    }
}

/// `exact plant (q += T u)`, or each kind's non-zero effects, e.g.
/// `prismatic joints: position resolution 1 mm; rotary joints: exact`.
impl std::fmt::Display for PlantModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PlantModel::Exact => f.write_str("exact plant (q += T u)"),
            PlantModel::LimitedPrecision { prismatic, rotary } => write!(
                f,
                "prismatic joints: {}; rotary joints: {}",
                describe(prismatic, 1e3, "mm"),
                describe(rotary, 1.0, "rad")
            ),
        }
    }
}

/// The non-zero effects of `p`, in `unit` (values scaled by `scale` from SI).
fn describe(p: &ActuatorPrecision, scale: f64, unit: &str) -> String {
    let parts: Vec<String> = [
        ("position resolution", p.position_resolution, ""),
        ("deadband", p.deadband, "/s"),
        ("velocity resolution", p.velocity_resolution, "/s"),
    ]
    .iter()
    .filter(|(_, value, _)| *value > 0.0)
    // Rounded to 1e-9 of the unit so that 1e-4 m prints as 0.1 mm.
    .map(|(name, value, per)| format!("{name} {} {unit}{per}", (value * scale * 1e9).round() / 1e9))
    .collect();
    if parts.is_empty() {
        "exact".into()
    } else {
        parts.join(", ")
    }
}

/// The simulated joints: a [`PlantModel`] with its state (each drive's
/// exact reference position and its encoder origin). Built once per run;
/// [`Plant::advance`] allocates nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct Plant {
    model: PlantModel,
    precision: Vec<Option<ActuatorPrecision>>,
    origin: Vec<f64>,
    reference: Vec<f64>,
}

impl Plant {
    /// The plant for joints of kinds `kinds` starting at `start` (m or rad).
    /// Errors: an invalid model, `start` not finite or of another length
    /// than `kinds`.
    pub fn new(model: PlantModel, kinds: &[JointKind], start: &[f64]) -> Result<Plant> {
        model.validate()?;
        check_finite_vector("start", start, kinds.len())?;
        Ok(Plant {
            model,
            precision: kinds.iter().map(|&k| model.precision(k)).collect(),
            origin: start.to_vec(),
            reference: start.to_vec(),
        })
    }

    /// The model.
    pub fn model(&self) -> PlantModel {
        self.model
    }

    /// Moves the joints `q` (m or rad, updated in place) under the commanded
    /// velocities `velocity` (m/s or rad/s) held for `sample_time` s. An
    /// exact joint does `q += T u` (bit for bit); a limited one integrates
    /// its realised velocity into the drive's reference and rests on the
    /// nearest position step. Errors: wrong sizes, non-finite values.
    pub fn advance(&mut self, q: &mut [f64], velocity: &[f64], sample_time: f64) -> Result<()> {
        let n = self.precision.len();
        check_finite_vector("q", q, n)?;
        check_finite_vector("velocity", velocity, n)?;
        crate::error::check_positive("sample_time", sample_time)?;
        for (j, (qj, &u)) in q.iter_mut().zip(velocity).enumerate() {
            match self.precision[j] {
                None => {
                    *qj += sample_time * u;
                    self.reference[j] = *qj;
                }
                Some(p) => {
                    self.reference[j] += sample_time * p.realised_velocity(u);
                    *qj = p.realised_position(self.origin[j], self.reference[j]);
                }
            }
        }
        Ok(())
    }
}
