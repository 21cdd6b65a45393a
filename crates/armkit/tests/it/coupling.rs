//! Additive couplings attached to a built model (`Model::with_coupling`):
//! each index, the target's kind and the target's drive are checked, the
//! error naming what is wrong; and the law's one-line description.

use armkit::beam::CarriageDeflection;
use armkit::model::{CouplingCurve, CouplingLaw, JointCoupling};
use armkit::Model;
use std::sync::Arc;

fn beam_coupling(source: usize, target: usize) -> JointCoupling {
    JointCoupling {
        source,
        target,
        law: CouplingLaw::Additive(Arc::new(CarriageDeflection::seed000())),
    }
}

/// The error `model.with_coupling` gives for `coupling`, as text.
fn refused(model: &Model, coupling: JointCoupling) -> String {
    let err = model.with_coupling(Some(coupling)).unwrap_err().to_string();
    assert!(err.contains("coupling"), "{err}");
    err
}

/// gantry9: three prismatic joints (0, 1, 2), then six revolute (3 to 8),
/// nine on the chain and in the configuration.
#[test]
fn an_additive_coupling_needs_indices_in_range_and_a_distinct_prismatic_target() {
    let gantry = armkit::robots::gantry9().unwrap();
    assert_eq!((gantry.dof(), gantry.chain_joints().len()), (9, 9));
    // Accepted: any source in range, the last one included, onto a
    // prismatic joint other than the source.
    for (source, target) in [(1, 2), (8, 2), (0, 1), (2, 0)] {
        let coupled = gantry.with_coupling(Some(beam_coupling(source, target)));
        let coupled = coupled.unwrap_or_else(|e| panic!("{source} -> {target}: {e}"));
        assert_eq!(coupled.couplings().len(), 1);
        assert_eq!(
            (coupled.couplings()[0].source, coupled.couplings()[0].target),
            (source, target)
        );
    }
    // A source one past the configuration, alone out of range.
    let err = refused(&gantry, beam_coupling(9, 2));
    assert!(
        err.contains("must index the model's 9 independent joints"),
        "{err}"
    );
    // A target one past the chain, alone out of range (not reported as a
    // revolute or missing joint: the index is checked first).
    let err = refused(&gantry, beam_coupling(1, 9));
    assert!(err.contains("its 9 chain joints"), "{err}");
    // Source and target the same prismatic joint.
    let err = refused(&gantry, beam_coupling(2, 2));
    assert!(err.contains("different joints"), "{err}");
    // A revolute target, the first and the last.
    for target in [3, 8] {
        let err = refused(&gantry, beam_coupling(1, target));
        assert!(
            err.contains(&format!("target joint {target} must be prismatic")),
            "{err}"
        );
    }
}

/// On a chain with mimic joints the target indexes the chain (9 joints)
/// and the source the configuration (7): a mimic joint cannot be a target,
/// and a source past the configuration is refused even where the chain is
/// longer.
#[test]
fn an_additive_coupling_cannot_drive_a_mimic_joint_and_its_source_is_a_configuration_index() {
    let finger = armkit::urdf::load(
        crate::common::data_path("urdf/mimicbot.urdf"),
        &armkit::urdf::ChainSelection::between("base", "fingertip"),
    )
    .unwrap();
    assert_eq!((finger.dof(), finger.chain_joints().len()), (7, 9));
    for target in [7, 8] {
        let err = refused(&finger, beam_coupling(0, target));
        assert!(
            err.contains(&format!("target joint {target} is a mimic joint")),
            "{err}"
        );
    }
    let err = refused(&finger, beam_coupling(7, 8));
    assert!(
        err.contains("must index the model's 7 independent joints"),
        "{err}"
    );
}

#[test]
fn a_coupling_law_describes_itself_in_one_line() {
    let mimic = CouplingLaw::Mimic {
        multiplier: -0.5,
        offset: 0.25,
    };
    assert_eq!(mimic.describe(), "mimic: multiplier -0.5, offset 0.25");
    let curve = CarriageDeflection::seed000();
    let additive = CouplingLaw::Additive(Arc::new(curve));
    assert_eq!(additive.describe(), format!("adds {}", curve.describe()));
    assert!(!curve.describe().is_empty());
}

/// A curve that gives only its value and slope.
#[derive(Debug)]
struct LinearSag;

impl CouplingCurve for LinearSag {
    fn value_and_slope(&self, x: f64) -> (f64, f64) {
        (-1e-3 * x, -1e-3)
    }

    fn describe(&self) -> String {
        "a sag of 1 mm per metre".into()
    }
}

/// A curve that does not give its second derivative has none anywhere and
/// no parameters to check; it couples the kinematics, and the dynamics,
/// which need the curvature, refuse the model and name the curve.
#[test]
fn a_curve_without_a_second_derivative_couples_kinematics_but_not_dynamics() {
    for x in [-1.0, 0.0, 0.5, 3.0, f64::NAN] {
        assert_eq!(LinearSag.second_derivative(x), None);
    }
    assert!(LinearSag.validate().is_ok());
    let gantry = armkit::robots::gantry9().unwrap();
    armkit::dynamics::check_dynamics_model(&gantry).unwrap();
    let coupling = JointCoupling {
        source: 1,
        target: 2,
        law: CouplingLaw::Additive(Arc::new(LinearSag)),
    };
    let sagging = gantry.with_coupling(Some(coupling)).unwrap();
    let q = [0.5, 2.0, 0.3, 0.1, -0.4, 0.7, 0.2, 0.9, -0.3];
    let mut chain = [0.0; 9];
    sagging.chain_positions(&q, &mut chain).unwrap();
    assert_eq!(chain[2], 0.3 - 2e-3);
    let err = armkit::dynamics::check_dynamics_model(&sagging)
        .unwrap_err()
        .to_string();
    assert!(err.contains("no second derivative"), "{err}");
    assert!(err.contains("a sag of 1 mm per metre"), "{err}");
    // The beam's curve gives it: the flexible gantry has dynamics.
    let flex = armkit::robots::by_name("gantry9-flex").unwrap();
    armkit::dynamics::check_dynamics_model(&flex).unwrap();
}

/// A mimic law's contribution is the whole target position `m x + o` and
/// its slope `m`: on the finger (a mimic of a mimic included) each mimic
/// coupling's law, at its source's position, gives the position forward
/// kinematics evaluates the chain at.
#[test]
fn a_mimic_laws_offset_and_slope_give_the_chain_positions() {
    let law = CouplingLaw::Mimic {
        multiplier: -1.5,
        offset: 0.25,
    };
    for x in [-2.0, -0.5, 0.0, 0.75, 3.0] {
        assert_eq!(law.offset_and_slope(x), (-1.5 * x + 0.25, -1.5));
    }
    let finger = armkit::urdf::load(
        crate::common::data_path("urdf/mimicbot.urdf"),
        &armkit::urdf::ChainSelection::between("base", "fingertip"),
    )
    .unwrap();
    let mut data = armkit::kinematics::Data::new(&finger);
    let mut rng = crate::common::rng(41);
    let mut mimics = 0;
    for _ in 0..20 {
        let q = crate::common::random_configuration(&finger, &mut rng);
        armkit::kinematics::forward_kinematics(&finger, &mut data, &q).unwrap();
        for coupling in finger.couplings() {
            let CouplingLaw::Mimic { multiplier, .. } = coupling.law else {
                continue;
            };
            mimics += 1;
            let (position, slope) = coupling.law.offset_and_slope(q[coupling.source]);
            assert_eq!(slope, multiplier);
            assert!(
                (position - data.effective_positions()[coupling.target]).abs() < 1e-15,
                "joint {}: {position} vs {}",
                coupling.target,
                data.effective_positions()[coupling.target]
            );
        }
    }
    assert_eq!(mimics, 40);
}
