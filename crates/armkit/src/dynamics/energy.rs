//! Kinetic and potential energy of the chain.

use super::spatial::Motion;
use super::DynamicsData;
use crate::error::{check_finite_vector, Result};
use crate::model::Model;

/// Kinetic energy `T = v' M(q) v / 2` (J) at positions `q` and velocities
/// `v`, summed body by body (`v_j' I_j v_j / 2`, world frame). Also leaves
/// the body velocities in [`DynamicsData::body_velocities`]. Errors as
/// [`super::rnea`]. Allocates nothing.
pub fn kinetic_energy(model: &Model, data: &mut DynamicsData, q: &[f64], v: &[f64]) -> Result<f64> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    data.update_bodies(model, q)?;
    let mut velocity = Motion::ZERO;
    let mut energy = 0.0;
    for (((axis, body), slot), &qd) in data
        .axes
        .iter()
        .zip(&data.bodies)
        .zip(data.velocities.iter_mut())
        .zip(v)
    {
        velocity = velocity + *axis * qd;
        *slot = velocity;
        energy += body.kinetic_energy(&velocity);
    }
    Ok(energy)
}

/// Potential energy `U = -sum_j m_j g . c_j` (J) of the links in the
/// workspace's gravity `g` (world frame), `c_j` each link's centre of mass in
/// the world frame: zero when every centre of mass is at the world origin's
/// height (for gravity along -z). Its gradient is
/// [`super::gravity_torques`]. Errors as [`super::rnea`]. Allocates nothing.
pub fn potential_energy(model: &Model, data: &mut DynamicsData, q: &[f64]) -> Result<f64> {
    data.update_bodies(model, q)?;
    let gravity = data.gravity;
    Ok(-data
        .bodies
        .iter()
        .map(|body| gravity.dot(&body.first_moment))
        .sum::<f64>())
}
