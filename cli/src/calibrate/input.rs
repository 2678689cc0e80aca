//! Measured throw files: JSON (the shared calibration set's schema, or a bare array of
//! its points) and CSV, read with a size bound and checked point by point.
//!
//! A point is a stun, follow, draw or spun cue ball at a cut angle and speed, and the
//! object ball's measured throw:
//!
//! | key / column | meaning |
//! |---|---|
//! | `cut_deg` | cut angle φ, degrees, in [0, 90) |
//! | `speed_mps` | cue-ball speed U before impact, m/s, in (0, 100] |
//! | `spin` | `stun`, `follow` (natural roll), `draw` (backspin of natural roll's size), or a number: the spin ratio, cue-ball spin as a multiple of natural roll (1 follow, −1 draw, 0 stun); stun when absent |
//! | `spin_rad_s` (JSON, also `cli_spin_rad_s`) or `wx_rad_s`, `wy_rad_s`, `wz_rad_s` (CSV) | the cue-ball spin in rad/s in the collision frame instead (x cue → object, z up; topspin `wy > 0`) |
//! | `throw_deg` | measured throw, degrees (towards the cue ball's tangential motion: positive for a positive cut) |
//! | `uncertainty_deg` | optional, > 0: the point's standard uncertainty (weights `1/u²`) |
//! | `id`, `series` | optional labels; `series` (JSON also `speed_label`) groups points for `--cross-validate`, by default the speed |
//!
//! JSON: `{"points": [ {...}, ... ]}` (other top-level keys and other point keys are
//! ignored, so the shared file reads as it is) or `[ {...}, ... ]`. CSV: a header line
//! naming the columns (any order; blank lines and lines starting with `#` skipped),
//! then one point per line, comma-separated, no quoting.

use std::fmt;
use std::io::Read;
use std::path::Path;

use serde::de::{self, Deserializer};
use serde::Deserialize;

mod csv;
pub use csv::parse_csv;

/// Largest file `calibrate` reads (bytes).
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// Cue-ball spin of a measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spin {
    /// A multiple of natural roll for the cue ball's velocity (0 stun, 1 follow, −1 draw).
    Ratio(f64),
    /// Angular velocity (rad/s) in the collision frame.
    RadPerSecond([f64; 3]),
}

impl Spin {
    /// The spin vector (rad/s, collision frame) for a cue ball of `speed` (m/s) at
    /// `cut_deg` and radius `radius` (m): natural roll is `ẑ × v / R`.
    pub fn vector(self, speed: f64, cut_deg: f64, radius: f64) -> [f64; 3] {
        match self {
            Spin::Ratio(r) => {
                let phi = cut_deg.to_radians();
                let k = r * speed / radius;
                [-k * phi.sin(), k * phi.cos(), 0.0]
            }
            Spin::RadPerSecond(w) => w,
        }
    }

    /// Short label: `stun`, `follow`, `draw`, `ratio 0.5` or `w (x,y,z)`.
    pub fn label(self) -> String {
        match self {
            Spin::Ratio(0.0) => "stun".to_owned(),
            Spin::Ratio(1.0) => "follow".to_owned(),
            Spin::Ratio(-1.0) => "draw".to_owned(),
            Spin::Ratio(r) => format!("ratio {r}"),
            Spin::RadPerSecond(w) if w == [0.0; 3] => "stun".to_owned(),
            Spin::RadPerSecond([x, y, z]) => format!("w ({x},{y},{z})"),
        }
    }
}

/// One measured throw.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// Label (the file's `id`, or `line N` / `point N`).
    pub id: String,
    /// Group for cross-validation.
    pub series: String,
    /// Cut angle φ (degrees), in [0, 90).
    pub cut_deg: f64,
    /// Cue-ball speed (m/s).
    pub speed_mps: f64,
    /// Cue-ball spin.
    pub spin: Spin,
    /// Measured throw (degrees).
    pub throw_deg: f64,
    /// Standard uncertainty (degrees), if the file gives one.
    pub uncertainty_deg: Option<f64>,
}

/// Why a file was refused: one line naming the file and the line, point or cause.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputError(pub String);

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Read at most [`MAX_FILE_BYTES`] of `path` and parse it: JSON if the extension is
/// `.json` or the text starts with `{` or `[`, CSV otherwise.
pub fn read_file(path: &Path) -> Result<Vec<Measurement>, InputError> {
    let shown = path.display();
    let file = std::fs::File::open(path).map_err(|e| InputError(format!("{shown}: {e}")))?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| InputError(format!("{shown}: {e}")))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(InputError(format!(
            "{shown}: larger than {MAX_FILE_BYTES} bytes (1 MiB), refused"
        )));
    }
    let text = String::from_utf8(bytes)
        .map_err(|e| InputError(format!("{shown}: not UTF-8 text ({e})")))?;
    let is_json = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
        || text.trim_start().starts_with(['{', '[']);
    let parsed = if is_json {
        parse_json(&text)
    } else {
        parse_csv(&text)
    };
    parsed.map_err(|e| InputError(format!("{shown}: {e}")))
}

/// Deserialize a finite number checked against `[lo, hi)` or `(lo, hi]` by `check`;
/// serde_json adds the line and column to the error.
fn checked<'de, D: Deserializer<'de>>(
    d: D,
    name: &str,
    check: fn(f64) -> Option<&'static str>,
) -> Result<f64, D::Error> {
    let v = f64::deserialize(d)?;
    match check(v) {
        None => Ok(v),
        Some(range) => Err(de::Error::custom(format!(
            "{name} = {v} is outside {range}"
        ))),
    }
}

fn check_cut(v: f64) -> Option<&'static str> {
    (!(v.is_finite() && (0.0..90.0).contains(&v))).then_some("[0, 90) degrees")
}

fn check_speed(v: f64) -> Option<&'static str> {
    (!(v.is_finite() && v > 0.0 && v <= 100.0)).then_some("(0, 100] m/s")
}

fn check_throw(v: f64) -> Option<&'static str> {
    (!(v.is_finite() && v.abs() < 90.0)).then_some("(-90, 90) degrees")
}

fn check_uncertainty(v: f64) -> Option<&'static str> {
    (!(v.is_finite() && v > 0.0 && v < 90.0)).then_some("(0, 90) degrees")
}

fn cut<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    checked(d, "cut_deg", check_cut)
}
fn speed<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    checked(d, "speed_mps", check_speed)
}
fn throw<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    checked(d, "throw_deg", check_throw)
}
fn uncertainty<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    Option::<f64>::deserialize(d)?
        .map(|v| match check_uncertainty(v) {
            None => Ok(v),
            Some(range) => Err(de::Error::custom(format!(
                "uncertainty_deg = {v} is outside {range}"
            ))),
        })
        .transpose()
}

/// The spin key of a JSON point: a name or a ratio.
#[derive(Deserialize)]
#[serde(untagged)]
enum SpinValue {
    Name(String),
    Ratio(f64),
}

fn spin_name(name: &str) -> Option<f64> {
    match name.trim().to_ascii_lowercase().as_str() {
        "stun" => Some(0.0),
        "follow" | "roll" => Some(1.0),
        "draw" => Some(-1.0),
        _ => None,
    }
}

fn spin_value<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    match Option::<SpinValue>::deserialize(d)? {
        None => Ok(None),
        Some(SpinValue::Ratio(r)) if r.is_finite() && r.abs() <= 10.0 => Ok(Some(r)),
        Some(SpinValue::Ratio(r)) => Err(de::Error::custom(format!(
            "spin ratio {r} is outside [-10, 10]"
        ))),
        Some(SpinValue::Name(name)) => spin_name(&name).map(Some).ok_or_else(|| {
            de::Error::custom(format!(
                "spin '{name}' is not stun, follow, draw or a number (spin ratio)"
            ))
        }),
    }
}

fn spin_vector<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 3]>, D::Error> {
    let w = Option::<[f64; 3]>::deserialize(d)?;
    match w {
        Some(w) if !w.iter().all(|x| x.is_finite() && x.abs() <= 1e4) => Err(de::Error::custom(
            "spin_rad_s components must be finite, |w| <= 1e4 rad/s",
        )),
        w => Ok(w),
    }
}

#[derive(Deserialize)]
struct JsonPoint {
    id: Option<String>,
    series: Option<String>,
    speed_label: Option<String>,
    #[serde(deserialize_with = "cut")]
    cut_deg: f64,
    #[serde(deserialize_with = "speed")]
    speed_mps: f64,
    #[serde(default, deserialize_with = "spin_value")]
    spin: Option<f64>,
    #[serde(default, deserialize_with = "spin_vector", alias = "cli_spin_rad_s")]
    spin_rad_s: Option<[f64; 3]>,
    #[serde(deserialize_with = "throw")]
    throw_deg: f64,
    #[serde(default, deserialize_with = "uncertainty")]
    uncertainty_deg: Option<f64>,
}

/// Parse JSON text (see the module docs). Errors name the line and column.
pub fn parse_json(text: &str) -> Result<Vec<Measurement>, InputError> {
    // Decide the shape first (an `untagged` enum would hide a point's error behind
    // "did not match any variant"), then deserialize it for its precise error.
    let points = if text.trim_start().starts_with('[') {
        serde_json::from_str::<Vec<JsonPoint>>(text)
    } else {
        #[derive(Deserialize)]
        struct Object {
            points: Vec<JsonPoint>,
        }
        serde_json::from_str::<Object>(text).map(|o| o.points)
    }
    .map_err(|e| InputError(one_line(&e.to_string())))?;
    Ok(points
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            let id = p.id.unwrap_or_else(|| format!("point {}", i + 1));
            let spin = match (p.spin_rad_s, p.spin) {
                (Some(w), _) => Spin::RadPerSecond(w),
                (None, r) => Spin::Ratio(r.unwrap_or(0.0)),
            };
            Measurement {
                id,
                series: p
                    .series
                    .or(p.speed_label)
                    .unwrap_or_else(|| format!("{} m/s", p.speed_mps)),
                cut_deg: p.cut_deg,
                speed_mps: p.speed_mps,
                spin,
                throw_deg: p.throw_deg,
                uncertainty_deg: p.uncertainty_deg,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_reads_every_spin_form() {
        let text = "# comment\ncut_deg,speed_mps,spin,throw_deg,uncertainty_deg\n30,2,stun,3.1,0.2\n30,2,follow,1.0,\n30,2,-0.5,2.0,0.3\n";
        let points = parse_csv(text).unwrap();
        assert_eq!(points.len(), 3);
        assert_eq!(points[0].spin, Spin::Ratio(0.0));
        assert_eq!(points[1].spin, Spin::Ratio(1.0));
        assert_eq!(points[1].uncertainty_deg, None);
        assert_eq!(points[2].spin, Spin::Ratio(-0.5));
        assert_eq!(points[2].id, "line 5");
    }

    #[test]
    fn natural_roll_vector_matches_the_core() {
        let w = Spin::Ratio(1.0).vector(2.0, 30.0, 0.028575);
        let core = cuesight::Impact::rolling(
            [
                2.0 * 30f32.to_radians().cos(),
                2.0 * 30f32.to_radians().sin(),
            ],
            0.028575,
        )
        .unwrap()
        .spin();
        assert!((w[0] - core.x as f64).abs() < 1e-3 && (w[1] - core.y as f64).abs() < 1e-3);
    }
}
