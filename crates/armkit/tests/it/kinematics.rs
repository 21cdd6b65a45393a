//! Forward kinematics and Jacobian: finite differences on every built-in
//! robot, frames, couplings and bad input.

use crate::common::*;
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{Matrix6xX, Pose};
use armkit::{Error, Model};

#[test]
fn jacobian_matches_finite_differences_on_every_builtin_robot() {
    let mut rng = rng(7);
    for entry in armkit::robots::BUILTIN {
        let model = (entry.build)().unwrap();
        assert_eq!(model.dof(), entry.dof, "{}", entry.name);
        let mut data = Data::new(&model);
        for _ in 0..50 {
            let q = random_configuration(&model, &mut rng);
            let analytic = jacobian(&model, &mut data, &q, JacobianFrame::World)
                .unwrap()
                .clone();
            let numeric = finite_difference_jacobian(&model, &q, 1e-6);
            let error = (&analytic - &numeric).amax();
            assert!(
                error < 1e-8,
                "{}: |J - J_fd| = {error:e} at {q:?}",
                entry.name
            );
        }
    }
}

/// The end-effector-frame Jacobian (tool axes) against finite differences
/// taken in tool axes, on every built-in robot: both its linear and its
/// angular rows are the tool's velocities in its own axes.
#[test]
fn end_effector_jacobian_matches_finite_differences_on_every_builtin_robot() {
    let mut rng = rng(37);
    for entry in armkit::robots::BUILTIN {
        let model = (entry.build)().unwrap();
        let mut data = Data::new(&model);
        for _ in 0..20 {
            let q = random_configuration(&model, &mut rng);
            let analytic = jacobian(&model, &mut data, &q, JacobianFrame::EndEffector)
                .unwrap()
                .clone();
            let numeric =
                finite_difference_jacobian_in(&model, &q, 1e-6, JacobianFrame::EndEffector);
            let error = (&analytic - &numeric).amax();
            assert!(
                error < 1e-8,
                "{}: |J_e - J_e,fd| = {error:e} at {q:?}",
                entry.name
            );
        }
    }
}

#[test]
fn end_effector_jacobian_is_the_world_jacobian_in_tool_axes() {
    let model = armkit::robots::panda().unwrap();
    let mut data = Data::new(&model);
    let q = [0.3, -0.5, 0.2, -2.0, 0.4, 1.8, -0.6];
    let world = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let rotation = data.end_effector_pose().rotation;
    let local = jacobian(&model, &mut data, &q, JacobianFrame::EndEffector)
        .unwrap()
        .clone();
    let mut rotated = Matrix6xX::zeros(7);
    for c in 0..7 {
        let v = rotation * local.fixed_view::<3, 1>(0, c);
        let w = rotation * local.fixed_view::<3, 1>(3, c);
        rotated.fixed_view_mut::<3, 1>(0, c).copy_from(&v);
        rotated.fixed_view_mut::<3, 1>(3, c).copy_from(&w);
    }
    assert!((rotated - world).amax() < 1e-14);
}

#[test]
fn joint_frames_end_at_the_end_effector_through_the_tool() {
    let model = armkit::robots::panda().unwrap();
    let mut data = Data::new(&model);
    let q = [0.1, 0.2, 0.3, -1.0, 0.5, 1.0, 0.7];
    let pose = *forward_kinematics(&model, &mut data, &q).unwrap();
    let last = data.joint_frames()[6];
    let rebuilt = last * *model.end_effector_placement();
    assert!((rebuilt.to_matrix4() - pose.to_matrix4()).amax() < 1e-15);
    // Modified DH: joint frames are the DH frames; the tool is the tool.
    assert!(
        (model.end_effector_placement().to_matrix4() - model.tool().to_matrix4()).amax() < 1e-15
    );
}

#[test]
fn base_transform_moves_everything_rigidly() {
    let model = armkit::robots::ur5().unwrap();
    let (convention, links) = model.dh_table().unwrap();
    let base = Pose::from_xyz_rpy([1.0, -2.0, 0.5], [0.1, 0.2, 0.3]);
    let moved =
        Model::from_dh_with_transforms("ur5-moved", convention, links, base, Pose::identity())
            .unwrap();
    let q = [0.4, -1.1, 1.3, 0.2, -0.7, 2.0];
    let mut data = Data::new(&model);
    let mut moved_data = Data::new(&moved);
    let pose = *forward_kinematics(&model, &mut data, &q).unwrap();
    let moved_pose = *forward_kinematics(&moved, &mut moved_data, &q).unwrap();
    assert!(((base * pose).to_matrix4() - moved_pose.to_matrix4()).amax() < 1e-14);
}

#[test]
fn wrong_size_non_finite_and_foreign_data_are_errors() {
    let model = armkit::robots::ur5().unwrap();
    let mut data = Data::new(&model);
    let err = forward_kinematics(&model, &mut data, &[0.0; 5]).unwrap_err();
    assert_eq!(
        err,
        Error::DimensionMismatch {
            what: "joint_positions",
            expected: 6,
            got: 5
        }
    );
    assert_eq!(err.to_string(), "joint_positions: expected 6 values, got 5");
    let err = jacobian(
        &model,
        &mut data,
        &[0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0],
        JacobianFrame::World,
    )
    .unwrap_err();
    assert_eq!(err.to_string(), "joint_positions[2] is not finite (NaN)");
    let panda = armkit::robots::panda().unwrap();
    let mut panda_data = Data::new(&panda);
    let err = forward_kinematics(&model, &mut panda_data, &[0.0; 6]).unwrap_err();
    assert!(err.to_string().contains("another model"), "{err}");
}

/// A workspace is tied to its model's independent joints and to its chain:
/// one made for a model that shares only one of the two counts is still
/// foreign. The mimic finger has 7 independent joints on a chain of 9; the
/// Panda has 7 on 7; the finger with its mimic tags removed has 9 on 9.
#[test]
fn data_sharing_only_the_dof_or_only_the_chain_length_is_foreign() {
    use armkit::urdf::{load, parse_str, ChainSelection};
    let finger_chain = ChainSelection::between("base", "fingertip");
    let finger = load(data_path("urdf/mimicbot.urdf"), &finger_chain).unwrap();
    let text = std::fs::read_to_string(data_path("urdf/mimicbot.urdf")).unwrap();
    let stripped: String = text
        .lines()
        .filter(|line| !line.trim_start().starts_with("<mimic"))
        .map(|line| format!("{line}\n"))
        .collect();
    let independent = parse_str(&stripped, "stripped", &finger_chain).unwrap();
    let panda = armkit::robots::panda().unwrap();
    assert_eq!((finger.dof(), finger.chain_joints().len()), (7, 9));
    assert_eq!((panda.dof(), panda.chain_joints().len()), (7, 7));
    assert_eq!(
        (independent.dof(), independent.chain_joints().len()),
        (9, 9)
    );
    let foreign = |model: &Model, data: &mut Data, q: &[f64]| {
        let fk = forward_kinematics(model, data, q).unwrap_err();
        assert!(fk.to_string().contains("another model"), "{fk}");
        let j = jacobian(model, data, q, JacobianFrame::World).unwrap_err();
        assert!(j.to_string().contains("another model"), "{j}");
    };
    // Same dof, another chain length, either way round.
    foreign(&finger, &mut Data::new(&panda), &[0.0; 7]);
    foreign(&panda, &mut Data::new(&finger), &[0.0; 7]);
    // Same chain length, another dof, either way round.
    foreign(&finger, &mut Data::new(&independent), &[0.0; 7]);
    foreign(&independent, &mut Data::new(&finger), &[0.0; 9]);
    // Each with its own workspace evaluates.
    for (model, q) in [(&finger, vec![0.0; 7]), (&panda, vec![0.0; 7])] {
        assert!(forward_kinematics(model, &mut Data::new(model), &q).is_ok());
    }
    assert!(forward_kinematics(&independent, &mut Data::new(&independent), &[0.0; 9]).is_ok());
}

#[test]
fn limits_check_names_the_joint() {
    let model = armkit::robots::panda().unwrap();
    let err = model
        .check_limits(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "joint 3 (`q4`) = 0 is outside its limits [-3.0718, -0.0698]"
    );
    assert!(model.check_limits(&model.neutral_configuration()).is_ok());
}

#[test]
fn a_pose_that_overflows_is_an_error_not_a_result() {
    // Finite inputs whose product overflows: lengths near f64::MAX.
    let text = "convention = \"standard\"\n[[links]]\ntype = \"P\"\nd = 1e308\na = 1e308\nalpha = 0\nqlim = [0, 1e308]\n[[links]]\ntype = \"R\"\nd = 1e308\na = 1e308\nalpha = 0\n";
    let model =
        armkit::description::parse_str(text, armkit::description::Format::Toml, "<huge>").unwrap();
    let mut data = Data::new(&model);
    let q = [1e308, 0.0];
    let fk = forward_kinematics(&model, &mut data, &q);
    assert!(
        matches!(&fk, Err(Error::Numerical { reason, .. }) if reason.contains("overflowed")),
        "{fk:?}"
    );
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World);
    assert!(matches!(j, Err(Error::Numerical { .. })), "{j:?}");
    // Even at zero the two offsets `d` add up past f64::MAX.
    assert!(forward_kinematics(&model, &mut data, &[0.0, 0.0]).is_err());
}

/// Forward kinematics and the Jacobian written out the plain way (index
/// loops over the public model: placements, joint kinds, couplings). The
/// library's loops (a coupling map matched once, slices zipped, the chain
/// product out of line) must give the same bits, on every built-in robot (gantry9-flex with its
/// beam coupling included).
#[test]
fn kinematics_equal_the_plain_product_bit_for_bit() {
    fn rotate(frame: &mut Pose, angle: f64) {
        let (s, c) = armkit::math::sin_cos(angle);
        let x = frame.rotation.column(0).into_owned();
        let y = frame.rotation.column(1).into_owned();
        frame.rotation.set_column(0, &(x * c + y * s));
        frame.rotation.set_column(1, &(y * c - x * s));
    }
    let mut rng = rng(15);
    for entry in armkit::robots::BUILTIN {
        let model = (entry.build)().unwrap();
        assert!(!model.has_mimic_joints(), "{}", entry.name);
        let mut data = Data::new(&model);
        for _ in 0..100 {
            let q = random_configuration(&model, &mut rng);
            let mut chain = q.clone();
            for coupling in model.couplings() {
                let (offset, _) = coupling.law.offset_and_slope(q[coupling.source]);
                chain[coupling.target] += offset;
            }
            let mut frame = Pose::identity();
            let mut frames = Vec::new();
            for (j, placement) in model.joint_placements().iter().enumerate() {
                frame = &frame * placement;
                if model.joints()[j].kind.is_rotational() {
                    rotate(&mut frame, chain[j]);
                } else {
                    frame.translation += frame.rotation.column(2) * chain[j];
                }
                frames.push(frame);
            }
            let end = &frame * model.end_effector_placement();
            let mut expected = Matrix6xX::zeros(model.dof());
            for (j, f) in frames.iter().enumerate() {
                let axis = f.rotation.column(2).into_owned();
                let mut column = expected.column_mut(j);
                if model.joints()[j].kind.is_rotational() {
                    let linear = axis.cross(&(end.translation - f.translation));
                    column.fixed_rows_mut::<3>(0).copy_from(&linear);
                    column.fixed_rows_mut::<3>(3).copy_from(&axis);
                } else {
                    column.fixed_rows_mut::<3>(0).copy_from(&axis);
                }
            }
            for coupling in model.couplings() {
                let (_, slope) = coupling.law.offset_and_slope(q[coupling.source]);
                let target = expected.column(coupling.target).into_owned();
                expected
                    .column_mut(coupling.source)
                    .axpy(slope, &target, 1.0);
            }
            let pose = *forward_kinematics(&model, &mut data, &q).unwrap();
            assert_eq!(pose, end, "{} at {q:?}", entry.name);
            assert_eq!(data.joint_frames(), frames.as_slice(), "{}", entry.name);
            assert_eq!(
                data.effective_positions(),
                chain.as_slice(),
                "{}",
                entry.name
            );
            let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
            assert_eq!(j, &expected, "{} at {q:?}", entry.name);
        }
    }
}

/// Every link frame of the UR5 and Panda URDF chains equals Pinocchio's joint
/// placement `oMi` (tests/data/reference_frames.json) to 1e-12, named by its
/// joint.
#[test]
fn link_frames_equal_pinocchio_joint_placements() {
    use armkit::kinematics::link_frames;
    let text = std::fs::read_to_string(crate::common::data_path("reference_frames.json")).unwrap();
    let reference: serde_json::Value = serde_json::from_str(&text).unwrap();
    let chains = reference["chains"].as_array().unwrap();
    assert_eq!(chains.len(), 2);
    for chain in chains {
        let model = armkit::urdf::load(
            crate::common::data_path(chain["urdf"].as_str().unwrap()),
            &armkit::urdf::ChainSelection::between(
                chain["base"].as_str().unwrap(),
                chain["tip"].as_str().unwrap(),
            ),
        )
        .unwrap();
        let names: Vec<&str> = model
            .chain_joints()
            .iter()
            .map(|j| j.name.as_str())
            .collect();
        let expected: Vec<&str> = chain["joint_names"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        assert_eq!(names, expected);
        let mut data = Data::new(&model);
        let mut frames = vec![armkit::math::Pose::identity(); names.len()];
        let samples = chain["samples"].as_array().unwrap();
        assert_eq!(samples.len(), 21);
        let mut worst = 0.0_f64;
        for sample in samples {
            let q: Vec<f64> = serde_json::from_value(sample["q"].clone()).unwrap();
            link_frames(&model, &mut data, &q, &mut frames).unwrap();
            for (frame, placement) in frames.iter().zip(sample["placements"].as_array().unwrap()) {
                let placement: Vec<f64> = serde_json::from_value(placement.clone()).unwrap();
                let matrix = frame.to_matrix4();
                for r in 0..4 {
                    for c in 0..4 {
                        worst = worst.max((matrix[(r, c)] - placement[4 * r + c]).abs());
                    }
                }
            }
        }
        println!(
            "{}: link frames vs Pinocchio oMi: worst {worst:.2e}",
            model.name()
        );
        assert!(worst < 1e-12, "{}: {worst:e}", model.name());
    }
    // A frames buffer of the wrong length is an error naming it.
    let model = armkit::robots::ur5().unwrap();
    let mut data = Data::new(&model);
    let err = link_frames(&model, &mut data, &[0.0; 6], &mut []).unwrap_err();
    assert!(err.to_string().contains("frames"), "{err}");
}

/// "Same name, different robot": the built-in `ur5-urdf` is `ur5` with its
/// poses in the UR URDF's `base_link`, so it gives the URDF's end-effector
/// pose (base_link -> tool0) at every configuration, and `ur5`'s pose turned
/// by 180 deg about z (and 0.3 mm lower, the two tables' d1).
#[test]
fn builtin_ur5_urdf_gives_the_urdf_poses_and_ur5s_turned_about_z() {
    let urdf = armkit::urdf::load(
        data_path("urdf/ur5.urdf"),
        &armkit::urdf::ChainSelection::between("base_link", "tool0"),
    )
    .unwrap();
    let builtin = armkit::robots::by_name("ur5-urdf").unwrap();
    let dh = armkit::robots::ur5().unwrap();
    assert_eq!(builtin.name(), "ur5-urdf");
    let (mut a, mut b, mut c) = (Data::new(&builtin), Data::new(&urdf), Data::new(&dh));
    let turn = Pose::trans_z(0.089159 - 0.089459) * Pose::rot_z(std::f64::consts::PI);
    let mut rng = rng(34);
    let (mut worst_urdf, mut worst_dh, mut apart) = (0.0_f64, 0.0_f64, 0.0_f64);
    for _ in 0..200 {
        let q = random_configuration(&builtin, &mut rng);
        let pose = *forward_kinematics(&builtin, &mut a, &q).unwrap();
        let reference = *forward_kinematics(&urdf, &mut b, &q).unwrap();
        let turned = turn * *forward_kinematics(&dh, &mut c, &q).unwrap();
        let (m, r, t) = (
            pose.to_matrix4(),
            reference.to_matrix4(),
            turned.to_matrix4(),
        );
        for i in 0..3 {
            for j in 0..4 {
                worst_urdf = worst_urdf.max((m[(i, j)] - r[(i, j)]).abs());
                worst_dh = worst_dh.max((m[(i, j)] - t[(i, j)]).abs());
            }
        }
        let dh_pose = forward_kinematics(&dh, &mut c, &q).unwrap().translation;
        apart = apart.max((dh_pose - reference.translation).norm());
    }
    println!("ur5-urdf vs ur5.urdf: {worst_urdf:.2e}; vs ur5 turned: {worst_dh:.2e}");
    // The URDF's origins are decimals (rounded at 1e-11 to 1e-12 of a
    // metre or radian): the two models agree to that.
    assert!(worst_urdf < 2e-11, "{worst_urdf:e}");
    assert!(worst_dh < 1e-12, "{worst_dh:e}");
    // The two built-ins are different frames of one arm (not a rounding).
    assert!(apart > 0.1, "{apart}");
    let (limits, dh_limits) = (builtin.position_limits(), dh.position_limits());
    assert_eq!(limits, dh_limits);
    assert!(builtin.has_inertias());
}
