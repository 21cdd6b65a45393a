//! The batched kernels (`kinematics::forward_kinematics_batch`,
//! `jacobian_batch`) against the single calls, configuration by
//! configuration, on every built-in robot, the URDF chains and a mimic-joint
//! chain, with the detected instructions (AVX2 + FMA where present) and the
//! baseline ones; the single calls' two builds against each other; and the
//! batched kernels' errors.

use armkit::kinematics::{
    forward_kinematics, forward_kinematics_batch, jacobian, jacobian_batch, BatchData, Data,
    InstructionSet, JacobianFrame, POSE_VALUES,
};
use armkit::urdf::{load, ChainSelection};
use armkit::Model;

use crate::common::{self, data_path, random_configuration, rng};

/// Tolerance of the comparisons (the 1e-14): the baseline lanes
/// round as the single call does, the AVX2 kernels fuse the frame's
/// multiply-adds (one rounding where the single call has two).
const TOLERANCE: f64 = 1e-14;

fn models() -> Vec<Model> {
    let mut models: Vec<Model> = armkit::robots::names()
        .map(|name| armkit::robots::by_name(name).unwrap())
        .collect();
    for (file, base, tip) in [
        ("urdf/ur5.urdf", "base_link", "tool0"),
        ("urdf/panda.urdf", "panda_link0", "panda_link8"),
        ("urdf/mimicbot.urdf", "base", "fingertip"),
    ] {
        models.push(load(data_path(file), &ChainSelection::between(base, tip)).unwrap());
    }
    assert!(models.iter().any(|m| m.has_mimic_joints()));
    assert!(models
        .iter()
        .any(|m| m.coupling().is_some() && !m.has_mimic_joints()));
    models
}

/// `count` random configurations (within limits; +-pi where unlimited), row-major.
fn configurations(model: &Model, count: usize, seed: u64) -> Vec<f64> {
    let mut rng = rng(seed);
    (0..count)
        .flat_map(|_| random_configuration(model, &mut rng))
        .collect()
}

#[test]
fn batched_fk_equals_the_single_call_on_every_model_and_both_instruction_sets() {
    // 13 configurations: three full blocks of four and a partial one.
    for model in models() {
        let dof = model.dof();
        let q = configurations(&model, 13, 7);
        let mut data = Data::new(&model);
        let mut expected = Vec::new();
        for row in q.chunks(dof) {
            let pose = forward_kinematics(&model, &mut data, row).unwrap();
            let m = pose.to_matrix4();
            for i in 0..4 {
                for j in 0..4 {
                    expected.push(m[(i, j)]);
                }
            }
        }
        for set in [InstructionSet::Detected, InstructionSet::Baseline] {
            let mut batch = BatchData::with_instruction_set(&model, set);
            let mut poses = vec![f64::NAN; 13 * POSE_VALUES];
            forward_kinematics_batch(&model, &mut batch, &q, &mut poses).unwrap();
            let d = common::max_abs_difference(&poses, &expected);
            assert!(d <= TOLERANCE, "{} {set:?}: {d:e}", model.name());
        }
    }
}

#[test]
fn batched_jacobians_equal_the_single_call_in_both_frames() {
    for model in models() {
        let dof = model.dof();
        let q = configurations(&model, 9, 11);
        let mut data = Data::new(&model);
        for frame in [JacobianFrame::World, JacobianFrame::EndEffector] {
            let mut expected = Vec::new();
            for row in q.chunks(dof) {
                let j = jacobian(&model, &mut data, row, frame).unwrap();
                for r in 0..6 {
                    for c in 0..dof {
                        expected.push(j[(r, c)]);
                    }
                }
            }
            for set in [InstructionSet::Detected, InstructionSet::Baseline] {
                let mut batch = BatchData::with_instruction_set(&model, set);
                let mut out = vec![f64::NAN; 9 * 6 * dof];
                jacobian_batch(&model, &mut batch, &q, frame, &mut out).unwrap();
                let d = common::max_abs_difference(&out, &expected);
                assert!(d <= TOLERANCE, "{} {frame:?} {set:?}: {d:e}", model.name());
            }
        }
    }
}

#[test]
fn the_two_instruction_sets_agree_on_large_batches_over_wide_angles() {
    // Angles over +-40 rad (several turns, every quadrant of the
    // reduction), 1001 configurations of the UR5.
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut rng = rng(3);
    let q: Vec<f64> = (0..1001 * 6)
        .map(|_| rand::Rng::gen_range(&mut rng, -40.0..40.0))
        .collect();
    let mut outs = Vec::new();
    for set in [InstructionSet::Detected, InstructionSet::Baseline] {
        let mut batch = BatchData::with_instruction_set(&model, set);
        let mut poses = vec![0.0; 1001 * POSE_VALUES];
        forward_kinematics_batch(&model, &mut batch, &q, &mut poses).unwrap();
        let mut jacobians = vec![0.0; 1001 * 36];
        jacobian_batch(&model, &mut batch, &q, JacobianFrame::World, &mut jacobians).unwrap();
        outs.push((poses, jacobians));
    }
    assert!(common::max_abs_difference(&outs[0].0, &outs[1].0) <= TOLERANCE);
    assert!(common::max_abs_difference(&outs[0].1, &outs[1].1) <= TOLERANCE);
}

#[test]
fn the_single_call_gives_the_same_bits_in_both_instruction_sets() {
    // The single call fuses nothing: its AVX2 build (sine-cosine four
    // joints per register) must give the baseline's bits, FK and Jacobian.
    for model in models() {
        let dof = model.dof();
        let q = configurations(&model, 25, 5);
        let mut detected = Data::with_instruction_set(&model, InstructionSet::Detected);
        let mut baseline = Data::with_instruction_set(&model, InstructionSet::Baseline);
        assert_eq!(baseline.instruction_set(), InstructionSet::Baseline);
        for row in q.chunks(dof) {
            let a = forward_kinematics(&model, &mut detected, row)
                .unwrap()
                .to_matrix4();
            let b = forward_kinematics(&model, &mut baseline, row)
                .unwrap()
                .to_matrix4();
            assert_eq!(a, b, "{} FK at {row:?}", model.name());
            assert_eq!(detected.joint_frames(), baseline.joint_frames());
            for frame in [JacobianFrame::World, JacobianFrame::EndEffector] {
                let a = jacobian(&model, &mut detected, row, frame).unwrap().clone();
                let b = jacobian(&model, &mut baseline, row, frame).unwrap();
                assert_eq!(&a, b, "{} {frame:?} Jacobian at {row:?}", model.name());
            }
        }
    }
}

#[test]
fn an_empty_batch_is_fine_and_bad_sizes_and_values_are_named() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut batch = BatchData::new(&model);
    forward_kinematics_batch(&model, &mut batch, &[], &mut []).unwrap();
    let mut poses = vec![0.0; 2 * POSE_VALUES];
    let err = forward_kinematics_batch(&model, &mut batch, &[0.0; 7], &mut poses).unwrap_err();
    assert!(err.to_string().contains("q"), "{err}");
    assert!(
        err.to_string().contains("6 values per configuration"),
        "{err}"
    );
    let err = forward_kinematics_batch(&model, &mut batch, &[0.0; 6], &mut poses).unwrap_err();
    assert!(err.to_string().contains("poses"), "{err}");
    let mut q = [0.0; 12];
    q[9] = f64::NAN;
    let err = forward_kinematics_batch(&model, &mut batch, &q, &mut poses).unwrap_err();
    assert!(
        err.to_string()
            .contains("configuration 1 (0-based), joint 3"),
        "{err}"
    );
    let mut jacobians = vec![0.0; 36];
    let err =
        jacobian_batch(&model, &mut batch, &q, JacobianFrame::World, &mut jacobians).unwrap_err();
    assert!(err.to_string().contains("jacobians"), "{err}");
    let panda = armkit::robots::by_name("panda").unwrap();
    let err =
        forward_kinematics_batch(&panda, &mut batch, &[0.0; 7], &mut poses[..16]).unwrap_err();
    assert!(err.to_string().contains("workspace"), "{err}");
}

#[test]
fn an_overflowing_configuration_is_an_error_naming_it() {
    // Finite inputs whose product overflows (as the single call's test):
    // lengths near f64::MAX, and a prismatic position of 1e308 in
    // configuration 5 only.
    let text = "convention = \"standard\"\n[[links]]\ntype = \"P\"\nd = 1e307\na = 1e307\nalpha = 0\nqlim = [0, 1e308]\n[[links]]\ntype = \"R\"\nd = 1e307\na = 1e307\nalpha = 0\n";
    let model =
        armkit::description::parse_str(text, armkit::description::Format::Toml, "<huge>").unwrap();
    let mut q = vec![0.0; 2 * 7];
    q[2 * 5] = f64::MAX;
    let mut batch = BatchData::new(&model);
    let mut poses = vec![0.0; 7 * POSE_VALUES];
    let err = forward_kinematics_batch(&model, &mut batch, &q, &mut poses).unwrap_err();
    assert!(err.to_string().contains("configuration 5"), "{err}");
    assert!(err.to_string().contains("overflowed"), "{err}");
    let mut jacobians = vec![0.0; 7 * 12];
    let err =
        jacobian_batch(&model, &mut batch, &q, JacobianFrame::World, &mut jacobians).unwrap_err();
    assert!(err.to_string().contains("configuration 5"), "{err}");
    // Without the huge position every pose is finite.
    q[2 * 5] = 0.0;
    forward_kinematics_batch(&model, &mut batch, &q, &mut poses).unwrap();
}

/// The batched FK of `q` against the single call, configuration by
/// configuration, in both instruction sets.
fn assert_batch_equals_single(model: &Model, batch: &mut BatchData, q: &[f64]) {
    let mut data = Data::new(model);
    let count = q.len() / model.dof();
    let mut poses = vec![f64::NAN; count * POSE_VALUES];
    forward_kinematics_batch(model, batch, q, &mut poses).unwrap();
    for (row, pose) in q.chunks(model.dof()).zip(poses.chunks(POSE_VALUES)) {
        let m = forward_kinematics(model, &mut data, row)
            .unwrap()
            .to_matrix4();
        let expected: Vec<f64> = (0..16).map(|k| m[(k / 4, k % 4)]).collect();
        let d = common::max_abs_difference(pose, &expected);
        assert!(d <= TOLERANCE, "{} at {row:?}: {d:e}", model.name());
    }
}

#[test]
fn angles_beyond_the_fast_reduction_take_the_checked_path_in_their_block() {
    // Lanes at 1e5 rad and beyond (and one just below) beside ordinary
    // ones: the block's sine-cosine goes lane by lane through the checked
    // routine, the other blocks stay on the vector one.
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut q = configurations(&model, 10, 17);
    q[6 * 2 + 1] = 1e5;
    q[6 * 3 + 4] = -3.5e7;
    q[6 * 9] = 99_999.9;
    for set in [InstructionSet::Detected, InstructionSet::Baseline] {
        assert_batch_equals_single(
            &model,
            &mut BatchData::with_instruction_set(&model, set),
            &q,
        );
    }
}

#[test]
fn a_workspace_follows_the_model_it_is_called_with() {
    // The workspace keeps the placements in lanes; each call takes them
    // from the model given, so a workspace of another model of the same
    // size computes that model's poses.
    let ur5 = armkit::robots::by_name("ur5").unwrap();
    let other = models()
        .into_iter()
        .find(|m| {
            m.dof() == 6
                && m.chain_joints().len() == 6
                && m.name() != ur5.name()
                && !m.has_mimic_joints()
                && m.coupling().is_none()
        })
        .expect("another 6-joint model");
    let mut batch = BatchData::new(&ur5);
    assert_batch_equals_single(&ur5, &mut batch, &configurations(&ur5, 5, 1));
    assert_batch_equals_single(&other, &mut batch, &configurations(&other, 5, 2));
    assert_batch_equals_single(&ur5, &mut batch, &configurations(&ur5, 5, 3));
}
