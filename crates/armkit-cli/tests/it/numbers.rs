//! Numbers on the command line: pi and degrees, named errors, wide rows.

use armkit_cli::common::{format_rows, parse_fixed_numbers, parse_numbers};

#[test]
fn numbers_parse_with_pi_and_degrees() {
    let v = parse_numbers("0.5, -1e-3, pi, -pi/2, 3*pi/4, 2pi, 90deg", "--q").unwrap();
    let pi = std::f64::consts::PI;
    let expected = [0.5, -1e-3, pi, -pi / 2.0, 0.75 * pi, 2.0 * pi, pi / 2.0];
    for (a, b) in v.iter().zip(expected) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
}

#[test]
fn bad_numbers_are_named() {
    assert_eq!(
        parse_numbers("1,x,3", "--q").unwrap_err().0,
        "--q: value 2: `x` is not a number"
    );
    assert_eq!(
        parse_numbers("1,nan", "--q").unwrap_err().0,
        "--q: value 2: `nan` is not a finite number"
    );
    assert_eq!(
        parse_numbers("", "--q").unwrap_err().0,
        "--q: no values given"
    );
    assert_eq!(
        parse_fixed_numbers("1,2", "--pose", 6).unwrap_err().0,
        "--pose: expected 6 values, got 2"
    );
}

#[test]
fn wide_numbers_stay_apart_in_a_row() {
    let text = format_rows(&[vec![225.974494, -636.429721, -1234567.0, 1.0]]);
    assert_eq!(
        text,
        "  [ 225.974494 -636.429721 -1234567.000000   1.000000 ]"
    );
}
