//! Example 02: a robot from a DH description (TOML), checked against its limits.
//!
//! Run: `cargo run --release --example 02_description_file`

use armkit::description::{parse_str, Format};
use armkit::kinematics::{forward_kinematics, Data};

const PLANAR_3R: &str = r#"
name = "planar3r"
convention = "standard"

[[links]]
type = "R"
d = 0.0
a = 0.5
alpha = 0.0
qlim = [-2.0, 2.0]

[[links]]
type = "R"
d = 0.0
a = 0.4
alpha = 0.0
qlim = [-2.5, 2.5]

[[links]]
type = "R"
d = 0.0
a = 0.1
alpha = 0.0
qlim = [-3.0, 3.0]
"#;

fn main() -> Result<(), armkit::Error> {
    let model = parse_str(PLANAR_3R, Format::Toml, "<planar3r>")?;
    let mut data = Data::new(&model);
    let q = [0.3, 0.6, -0.4];
    model.check_limits(&q)?;
    let pose = forward_kinematics(&model, &mut data, &q)?;
    println!(
        "{}: tool at {:.4?} m",
        model.name(),
        pose.translation.as_slice()
    );
    match model.check_limits(&[0.0, 3.0, 0.0]) {
        Err(e) => println!("as expected: {e}"),
        Ok(()) => println!("unexpectedly within limits"),
    }
    Ok(())
}
