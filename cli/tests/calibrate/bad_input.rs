//! Every bad-input class, through the library.

use cuesight_cli::calibrate::fit::stun;
use cuesight_cli::calibrate::input::{parse_csv, parse_json};
use cuesight_cli::calibrate::{fit, read_file, FitKind, FitOptions, Measurement};

use super::{shared_set, temp_file};

fn csv_error(text: &str) -> String {
    parse_csv(text).unwrap_err().to_string()
}

#[test]
fn missing_column_is_named() {
    let e = csv_error("cut_deg,speed_mps,spin\n30,2,stun\n");
    assert!(e.contains("line 1") && e.contains("throw_deg"), "{e}");
    let e = parse_json(r#"{"points":[{"cut_deg":30,"speed_mps":2}]}"#)
        .unwrap_err()
        .to_string();
    assert!(e.contains("throw_deg") && e.contains("line 1"), "{e}");
}

#[test]
fn cut_outside_0_90_is_named_with_its_line() {
    let e = csv_error("cut_deg,speed_mps,throw_deg\n30,2,3\n90,2,3\n");
    assert!(e.contains("line 3") && e.contains("cut_deg = 90"), "{e}");
    let e = csv_error("cut_deg,speed_mps,throw_deg\n-5,2,3\n");
    assert!(e.contains("line 2") && e.contains("[0, 90)"), "{e}");
    let e = parse_json("[\n{\"cut_deg\":30,\"speed_mps\":2,\"throw_deg\":3},\n{\"cut_deg\":95,\"speed_mps\":2,\"throw_deg\":3}\n]")
        .unwrap_err()
        .to_string();
    assert!(e.contains("cut_deg = 95") && e.contains("line 3"), "{e}");
}

#[test]
fn nan_and_junk_are_named() {
    let e = csv_error("cut_deg,speed_mps,throw_deg\n30,NaN,3\n");
    assert!(e.contains("line 2") && e.contains("speed_mps"), "{e}");
    let e = csv_error("cut_deg,speed_mps,throw_deg\n30,2,inf\n");
    assert!(e.contains("line 2") && e.contains("throw_deg"), "{e}");
    let e = csv_error("cut_deg,speed_mps,spin,throw_deg\n30,2,massé,3\n");
    assert!(e.contains("line 2") && e.contains("massé"), "{e}");
    let e = csv_error("cut_deg,speed_mps,throw_deg\n30,2\n");
    assert!(e.contains("line 2") && e.contains("2 fields"), "{e}");
    // JSON has no NaN: a syntax error with its line.
    let e = parse_json("{\"points\": [\n{\"cut_deg\": NaN, \"speed_mps\": 2, \"throw_deg\": 3}]}")
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 2"), "{e}");
}

#[test]
fn fewer_points_than_parameters_is_refused() {
    let points = vec![
        stun("a", "s", 30.0, 2.0, 3.0),
        stun("b", "s", 40.0, 2.0, 3.0),
    ];
    let e = fit(&points, &FitOptions::new(FitKind::MuV))
        .unwrap_err()
        .to_string();
    assert!(e.contains("2 points for 3 parameters"), "{e}");
}

#[test]
fn a_fit_that_does_not_converge_says_so() {
    let points = read_file(&shared_set()).unwrap();
    let mut options = FitOptions::new(FitKind::MuV);
    options.max_evaluations = 100;
    let e = fit(&points, &options).unwrap_err().to_string();
    assert!(e.contains("did not converge"), "{e}");
}

#[test]
fn unidentifiable_parameters_are_refused() {
    // One speed, cuts where every point grips: throw does not depend on μ at all.
    let points: Vec<Measurement> = (1..=6)
        .map(|k| stun(&k.to_string(), "s", k as f64, 3.0, 0.3 * k as f64))
        .collect();
    let e = fit(&points, &FitOptions::new(FitKind::MuV));
    assert!(e.is_err(), "{:?}", e.map(|f| f.estimates));
}

#[test]
fn a_file_over_1_mib_is_refused() {
    let mut big = b"cut_deg,speed_mps,throw_deg\n".to_vec();
    while big.len() <= 1 << 20 {
        big.extend_from_slice(b"30,2,3\n");
    }
    let path = temp_file("big.csv", &big);
    let e = read_file(&path).unwrap_err().to_string();
    assert!(e.contains("larger than 1048576 bytes"), "{e}");
}
