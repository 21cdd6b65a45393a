//! Checks of the command line's own input formats (scenario files, number
//! lists and poses) on arbitrary bytes: an `Err` is fine, a panic is a crash.

use std::path::Path;

use armkit_cli::common::{parse_numbers, parse_pose};

/// A scenario file (`armkit run FILE.toml`), parsed and validated (the robot
/// it names is loaded) but not run.
pub fn scenario(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return; // scenario::load reads UTF-8 text.
    };
    // A scenario may name a robot file by absolute path; reading a device
    // (/dev/zero, /dev/stdin) blocks or never ends by nature, not by a bug of
    // the parser, so such names are left out.
    if ["/dev", "/proc", "/sys"].iter().any(|p| text.contains(p)) {
        return;
    }
    // Relative robot files resolve in a folder that does not exist.
    let _ = armkit_cli::scenario::parse(text, "<fuzz>.toml", Path::new("/nonexistent-fuzz-dir"));
}

/// A number list (`--q 0.1,pi/2,90deg`) and a pose (`--pose x,y,z,r,p,y`):
/// what parses is finite, and a pose's rotation is orthonormal.
pub fn cli_numbers(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return; // clap hands the commands UTF-8 strings.
    };
    if let Ok(values) = parse_numbers(text, "--q") {
        assert!(
            values.iter().all(|v| v.is_finite()),
            "parse_numbers({text:?}) = {values:?} is not finite"
        );
    }
    if let Ok(pose) = parse_pose(text, "--pose") {
        let rows = pose.to_rows();
        assert!(
            rows.iter().flatten().all(|v| v.is_finite()),
            "parse_pose({text:?}) is not finite: {rows:?}"
        );
        let r = pose.rotation;
        let error = (r.transpose() * r - armkit::math::Matrix3::identity())
            .abs()
            .max();
        assert!(
            error < 1e-12 && (r.determinant() - 1.0).abs() < 1e-12,
            "parse_pose({text:?}): the rotation is not orthonormal (|R'R - I| = {error:e}, det = {})",
            r.determinant()
        );
    }
}
