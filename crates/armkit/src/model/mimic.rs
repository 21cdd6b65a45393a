//! Resolving mimic joints at build time: each mimic joint of the chain is
//! traced back to its first independent leader (a mimic of a mimic composes
//! the two affine maps), the configuration is made of the independent joints,
//! and each mimic joint's limits bound its leader through the map (the
//! tighter bound wins).

use std::collections::HashMap;

use super::coupling::{mimic_error, CouplingLaw, Drive, JointCoupling, MimicJoint};
use super::{Joint, JointKind, JointLimits};
use crate::error::Result;

/// What the resolution gives the model.
pub(super) struct Resolved {
    /// The configuration's joints, limits tightened by their followers.
    pub joints: Vec<Joint>,
    /// One per chain joint.
    pub drives: Vec<Drive>,
    /// One mimic coupling per mimic joint of the chain (resolved leader).
    pub couplings: Vec<JointCoupling>,
}

/// Resolves `mimics` over the chain joints `chain` and the joints `off_chain`
/// (leaders that are not on the chain). Errors name the joints: a mimic
/// declaration for an unknown joint, a leader that does not exist, a
/// non-finite multiplier or offset, a joint declared twice, a cycle, limits
/// that leave the leader no range.
pub(super) fn resolve(
    model: &str,
    chain: &[Joint],
    off_chain: &[Joint],
    mimics: &[MimicJoint],
) -> Result<Resolved> {
    let all: Vec<&Joint> = chain.iter().chain(off_chain).collect();
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, joint) in all.iter().enumerate() {
        if index.insert(joint.name.as_str(), i).is_some() {
            return Err(mimic_error(
                model,
                &joint.name,
                "two joints of the model have this name (mimic joints are resolved by name)",
            ));
        }
    }
    // Per joint (chain then off-chain): its declaration (leader index, m, o).
    let mut follows: Vec<Option<(usize, f64, f64)>> = vec![None; all.len()];
    for mimic in mimics {
        let Some(&follower) = index.get(mimic.joint.as_str()) else {
            return Err(mimic_error(
                model,
                &mimic.joint,
                "declared as a mimic joint, but the model has no joint of that name",
            ));
        };
        let Some(&leader) = index.get(mimic.leader.as_str()) else {
            return Err(mimic_error(
                model,
                &mimic.joint,
                format!(
                    "its leader `{}` is not a joint of the model (a mimic joint follows an existing joint)",
                    mimic.leader
                ),
            ));
        };
        for (what, value) in [("multiplier", mimic.multiplier), ("offset", mimic.offset)] {
            if !value.is_finite() {
                return Err(mimic_error(
                    model,
                    &mimic.joint,
                    format!("the {what} must be finite, got {value}"),
                ));
            }
        }
        if follows[follower].is_some() {
            return Err(mimic_error(
                model,
                &mimic.joint,
                "declared as a mimic joint twice",
            ));
        }
        follows[follower] = Some((leader, mimic.multiplier, mimic.offset));
    }

    // Each chain joint: (independent joint in `all`, multiplier, offset).
    let mut sources = Vec::with_capacity(chain.len());
    for j in 0..chain.len() {
        sources.push(trace(model, &all, &follows, j)?);
    }
    // Configuration order: first appearance along the chain.
    let mut variable_of: HashMap<usize, usize> = HashMap::new();
    let mut leaders: Vec<usize> = Vec::new();
    let mut drives = Vec::with_capacity(chain.len());
    let mut couplings = Vec::new();
    for (j, &(leader, multiplier, offset)) in sources.iter().enumerate() {
        let variable = *variable_of.entry(leader).or_insert_with(|| {
            leaders.push(leader);
            leaders.len() - 1
        });
        if follows[j].is_none() {
            drives.push(Drive::Independent(variable));
        } else {
            drives.push(Drive::Mimic {
                leader: variable,
                multiplier,
                offset,
            });
            couplings.push(JointCoupling {
                source: variable,
                target: j,
                law: CouplingLaw::Mimic { multiplier, offset },
            });
        }
    }
    let mut joints = Vec::with_capacity(leaders.len());
    for (variable, &leader) in leaders.iter().enumerate() {
        let mut joint = all[leader].clone();
        if leader >= chain.len() {
            // An off-chain leader moves no body of the chain.
            joint.inertia = None;
        }
        let followers: Vec<(&Joint, f64, f64)> = drives
            .iter()
            .zip(chain)
            .filter_map(|(drive, follower)| match *drive {
                Drive::Mimic {
                    leader,
                    multiplier,
                    offset,
                } if leader == variable => Some((follower, multiplier, offset)),
                _ => None,
            })
            .collect();
        joint.limits = tightened(model, &joint, &followers)?;
        if joint.kind == JointKind::Continuous && joint.limits.is_bounded() {
            // Bounded through a follower: the angle must no longer wrap.
            joint.kind = JointKind::Revolute;
        }
        joints.push(joint);
    }
    Ok(Resolved {
        joints,
        drives,
        couplings,
    })
}

/// Follows the mimic declarations from joint `start` to the first joint that
/// mimics nothing: `q_start = m q_leader + o`. A cycle is an error listing
/// its joints.
fn trace(
    model: &str,
    all: &[&Joint],
    follows: &[Option<(usize, f64, f64)>],
    start: usize,
) -> Result<(usize, f64, f64)> {
    let (mut multiplier, mut offset) = (1.0, 0.0);
    let mut path = vec![start];
    let mut current = start;
    while let Some((leader, m, o)) = follows[current] {
        // q = multiplier (m q_leader + o) + offset.
        offset += multiplier * o;
        multiplier *= m;
        if let Some(at) = path.iter().position(|&p| p == leader) {
            let names: Vec<String> = path[at..]
                .iter()
                .chain(std::iter::once(&leader))
                .map(|&p| format!("`{}`", all[p].name))
                .collect();
            return Err(mimic_error(
                model,
                &all[start].name,
                format!(
                    "the mimic joints form a cycle ({}): every chain of mimic joints must end at an independent joint",
                    names.join(" -> ")
                ),
            ));
        }
        path.push(leader);
        current = leader;
    }
    Ok((current, multiplier, offset))
}

/// The leader's limits intersected with what each follower's limits allow:
/// `lo <= m q + o <= hi` gives `q` in `[(lo - o)/m, (hi - o)/m]` (swapped for
/// `m < 0`); velocity and acceleration bounds divide by `|m|`. Bounds are
/// nudged inward until the followers' positions at the leader's bounds lie
/// within their limits in floating point.
fn tightened(model: &str, leader: &Joint, followers: &[(&Joint, f64, f64)]) -> Result<JointLimits> {
    let mut limits = leader.limits;
    for &(follower, m, o) in followers {
        let own = follower.limits;
        if m == 0.0 {
            if !own.contains(o) {
                return Err(mimic_error(
                    model,
                    &follower.name,
                    format!(
                        "multiplier 0 holds it at its offset {o}, outside its limits [{}, {}]",
                        own.lower, own.upper
                    ),
                ));
            }
            continue;
        }
        let (a, b) = ((own.lower - o) / m, (own.upper - o) / m);
        let (lower, upper) = if m > 0.0 { (a, b) } else { (b, a) };
        limits.lower = limits.lower.max(lower);
        limits.upper = limits.upper.min(upper);
        limits.velocity = tighter(limits.velocity, own.velocity.map(|v| v / m.abs()));
        limits.acceleration = tighter(limits.acceleration, own.acceleration.map(|v| v / m.abs()));
    }
    for _ in 0..8 {
        let mut changed = false;
        for &(follower, m, o) in followers {
            if m == 0.0 {
                continue;
            }
            for (bound, inward) in [
                (&mut limits.lower, f64::INFINITY),
                (&mut limits.upper, f64::NEG_INFINITY),
            ] {
                if bound.is_finite() && !follower.limits.contains(m * *bound + o) {
                    *bound = next_toward(*bound, inward);
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    if limits.lower > limits.upper || limits.lower.is_nan() || limits.upper.is_nan() {
        let names: Vec<String> = followers
            .iter()
            .map(|(f, ..)| format!("`{}`", f.name))
            .collect();
        return Err(mimic_error(
            model,
            followers
                .first()
                .map_or(leader.name.as_str(), |f| f.0.name.as_str()),
            format!(
                "the limits of the mimic joints {} leave their leader `{}` (limits [{}, {}]) no position at which all of them hold",
                names.join(", "),
                leader.name,
                leader.limits.lower,
                leader.limits.upper
            ),
        ));
    }
    Ok(limits)
}

fn tighter(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// The next representable `f64` after finite `x` in the direction of `toward`.
fn next_toward(x: f64, toward: f64) -> f64 {
    if x == 0.0 {
        return if toward > 0.0 {
            f64::from_bits(1)
        } else {
            -f64::from_bits(1)
        };
    }
    let bits = x.to_bits();
    let away_from_zero = (toward > x) == (x > 0.0);
    f64::from_bits(if away_from_zero { bits + 1 } else { bits - 1 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_toward_steps_one_ulp() {
        for x in [1.0, -1.0, 0.3, -2.5e-300] {
            let up = next_toward(x, f64::INFINITY);
            let down = next_toward(x, f64::NEG_INFINITY);
            assert!(up > x && down < x);
            assert_eq!(next_toward(up, f64::NEG_INFINITY), x);
            assert_eq!(next_toward(down, f64::INFINITY), x);
        }
        assert!(next_toward(0.0, 1.0) > 0.0 && next_toward(0.0, -1.0) < 0.0);
    }
}
