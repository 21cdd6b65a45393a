//! The claims of seed 000's examples (what the paper's text, or our
//! explanation, says each example shows), evaluated on a run.

use super::{MpcRun, Seed000Example};

impl Seed000Example {
    /// The claims the paper's text (or our explanation) makes for this
    /// example, evaluated on `run`.
    pub fn checks(self, run: &MpcRun) -> Vec<ExampleCheck> {
        let prismatic = run.prismatic_joints();
        let mut checks = vec![
            ExampleCheck::new(
                "no joint velocity limit crossed",
                run.summary.max_velocity_violation == 0.0,
                format!("max violation {:.3e}", run.summary.max_velocity_violation),
            ),
            ExampleCheck::new(
                "no joint position limit crossed",
                run.summary.max_position_violation == 0.0,
                format!("max violation {:.3e}", run.summary.max_position_violation),
            ),
        ];
        let peak_prismatic: Vec<f64> = prismatic.iter().map(|&j| run.peak_speed(j)).collect();
        let travel_prismatic: Vec<f64> = prismatic.iter().map(|&j| run.travel(j)).collect();
        let converged = ExampleCheck::new(
            "converges: at the target (1e-4 m) and at rest (1e-3)",
            run.summary.converged,
            format!(
                "{} steps ({:.2} s), final error {:.2e} m",
                run.summary.steps,
                run.summary.steps as f64 * run.sample_time,
                run.summary.final_position_error
            ),
        );
        let travel = format!(
            "travel d1, d2, d3 = {}",
            format_values(&travel_prismatic, "m")
        );
        match self {
            Seed000Example::LargeMove => {
                checks.push(converged);
                let saturated = peak_prismatic.iter().filter(|&&p| p >= 0.6 - 1e-9).count();
                checks.push(ExampleCheck::new(
                    "prismatic velocities reach 0.6 m/s without exceeding it",
                    saturated > 0 && peak_prismatic.iter().all(|&p| p <= 0.6),
                    format!(
                        "peak |v| d1, d2, d3 = {}",
                        format_values(&peak_prismatic, "m/s")
                    ),
                ));
                let final_speed = run.samples.iter().rev().nth(1).map_or(f64::NAN, |s| {
                    s.velocity.iter().fold(0.0, |m, v| m.max(v.abs()))
                });
                checks.push(ExampleCheck::new(
                    "all joint velocities settle to zero",
                    run.summary.converged && final_speed <= 1e-3,
                    format!("largest |v| at the last step {final_speed:.2e}"),
                ));
            }
            Seed000Example::SmallMove => {
                checks.push(converged);
                checks.push(ExampleCheck::new(
                    "prismatic joints travel less than 1 mm",
                    travel_prismatic.iter().all(|&d| d < 1e-3),
                    travel,
                ));
            }
            Seed000Example::SmallMovePaperWeights => {
                checks.push(converged);
                checks.push(ExampleCheck::new(
                    "with R = 100/10/1 the prismatic joints do move (> 1 mm): a 10:1 priority only scales their share",
                    travel_prismatic.iter().any(|&d| d >= 1e-3),
                    travel,
                ));
            }
            Seed000Example::EqualWeights => {
                checks.push(ExampleCheck::new(
                    "prismatic joints move (more than 1 mm)",
                    travel_prismatic.iter().any(|&d| d >= 1e-3),
                    travel,
                ));
                checks.push(converged);
            }
            Seed000Example::EqualWeightsUndamped => {
                let reached = run.samples.iter().any(|s| s.position_error <= 1e-4);
                checks.push(ExampleCheck::new(
                    "the hand reaches the target (1e-4 m)",
                    reached,
                    format!("final error {:.2e} m", run.summary.final_position_error),
                ));
                let last_speed = run.samples.iter().rev().nth(1).map_or(f64::NAN, |s| {
                    s.velocity.iter().fold(0.0, |m, v| m.max(v.abs()))
                });
                checks.push(ExampleCheck::new(
                    "but the joints never settle: self-motion is undamped without a velocity term",
                    !run.summary.converged && last_speed > 1e-3,
                    format!(
                        "after {} steps largest |v| = {last_speed:.3}; rotary travel {}",
                        run.summary.steps,
                        format_values(
                            &run.rotary_joints()
                                .iter()
                                .map(|&j| run.travel(j))
                                .collect::<Vec<_>>(),
                            "rad"
                        )
                    ),
                ));
            }
        }
        checks
    }
}

fn format_values(values: &[f64], unit: &str) -> String {
    let parts: Vec<String> = values.iter().map(|v| format!("{v:.4}")).collect();
    format!("[{}] {unit}", parts.join(", "))
}

/// One check of an example: what is claimed, whether it holds, the numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct ExampleCheck {
    /// The claim.
    pub name: String,
    /// Whether it holds.
    pub passed: bool,
    /// The measured values.
    pub detail: String,
}

impl ExampleCheck {
    fn new(name: &str, passed: bool, detail: String) -> Self {
        ExampleCheck {
            name: name.to_string(),
            passed,
            detail,
        }
    }
}
