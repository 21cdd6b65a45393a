//! Kinetic and potential energy of the chain.

use super::spatial::Motion;
use super::{check_not_overflowed, DynamicsData};
use crate::error::{check_finite_vector, Result};
use crate::model::Model;

/// Kinetic energy `T = v' M(q) v / 2` (J) at positions `q` and velocities
/// `v`, summed body by body (`v_j' I_j v_j / 2`, each body in its own joint
/// frame). Also leaves the body velocities in
/// [`DynamicsData::body_velocities`]. Errors as [`super::rnea`]. Allocates
/// nothing.
pub fn kinetic_energy(model: &Model, data: &mut DynamicsData, q: &[f64], v: &[f64]) -> Result<f64> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    data.update_transforms(model, q)?;
    // A coupled model's chain moves at M v; take the buffer out to keep the
    // per-body ones borrowable.
    let mut coupled = data.coupled.take();
    let chain_velocities = match &mut coupled {
        None => v,
        Some(coupled) => {
            coupled.expand(v, None);
            &coupled.chain_velocities
        }
    };
    let mut velocity = Motion::ZERO;
    let mut energy = 0.0;
    for (j, &qd) in chain_velocities.iter().enumerate() {
        // v_j = X_j v_{j-1} + S qd_j (Featherstone table 5.1).
        velocity = velocity.inverse_transformed(&data.transforms[j]);
        data.joint_axes[j].add_rate(&mut velocity, qd);
        data.velocities[j] = velocity;
        energy += data.local_inertias[j].kinetic_energy(&velocity);
    }
    data.coupled = coupled;
    check_not_overflowed("kinetic energy", &[energy])?;
    Ok(energy)
}

/// Potential energy `U = -sum_j m_j g . c_j` (J) of the links in the
/// workspace's gravity `g` (world frame), `c_j` each link's centre of mass in
/// the world frame: zero when every centre of mass is at the world origin's
/// height (for gravity along -z). Its gradient is
/// [`super::gravity_torques`]. Errors as [`super::rnea`]. Allocates nothing.
pub fn potential_energy(model: &Model, data: &mut DynamicsData, q: &[f64]) -> Result<f64> {
    data.update_transforms(model, q)?;
    data.update_world_bodies();
    let gravity = data.gravity;
    let energy = -data
        .world_inertias
        .iter()
        .map(|body| gravity.dot(&body.first_moment))
        .sum::<f64>();
    check_not_overflowed("potential energy", &[energy])?;
    Ok(energy)
}
