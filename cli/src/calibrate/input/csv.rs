//! CSV measured-throw files (see the parent module for the columns): a header line
//! naming the columns in any order, then one point per line; errors name the line.

use super::{
    check_cut, check_speed, check_throw, check_uncertainty, spin_name, InputError, Measurement,
    Spin,
};

/// Parse CSV text (see the module docs). Errors name the line.
pub fn parse_csv(text: &str) -> Result<Vec<Measurement>, InputError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((header_line, header)) = lines.next() else {
        return Err(InputError("no header line (empty CSV)".to_owned()));
    };
    let names: Vec<String> = header
        .split(',')
        .map(|s| s.trim().to_ascii_lowercase())
        .collect();
    let column = |name: &str| names.iter().position(|n| n == name);
    let required = |name: &str| {
        column(name).ok_or_else(|| {
            InputError(format!(
                "line {header_line}: missing column `{name}` (header: {header})"
            ))
        })
    };
    let (cut_col, speed_col, throw_col) = (
        required("cut_deg")?,
        required("speed_mps")?,
        required("throw_deg")?,
    );
    let spin_col = column("spin");
    let w_cols = ["wx_rad_s", "wy_rad_s", "wz_rad_s"].map(column);
    let w_cols = match w_cols {
        [Some(x), Some(y), Some(z)] => Some([x, y, z]),
        [None, None, None] => None,
        _ => {
            return Err(InputError(format!(
                "line {header_line}: give all three of wx_rad_s, wy_rad_s, wz_rad_s or none"
            )))
        }
    };
    if spin_col.is_some() && w_cols.is_some() {
        return Err(InputError(format!(
            "line {header_line}: give either a `spin` column or wx_rad_s, wy_rad_s, wz_rad_s, not both"
        )));
    }
    let (id_col, series_col, u_col) = (column("id"), column("series"), column("uncertainty_deg"));
    let mut out = Vec::new();
    for (n, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != names.len() {
            return Err(InputError(format!(
                "line {n}: {} fields, the header has {}",
                fields.len(),
                names.len()
            )));
        }
        let number = |col: usize, check: fn(f64) -> Option<&'static str>| {
            let text = fields[col];
            let v: f64 = text.parse().map_err(|_| {
                InputError(format!("line {n}: {} '{text}' is not a number", names[col]))
            })?;
            match check(v) {
                None => Ok(v),
                Some(range) => Err(InputError(format!(
                    "line {n}: {} = {v} is outside {range}",
                    names[col]
                ))),
            }
        };
        let cut_deg = number(cut_col, check_cut)?;
        let speed_mps = number(speed_col, check_speed)?;
        let throw_deg = number(throw_col, check_throw)?;
        let uncertainty_deg = match u_col {
            Some(col) if !fields[col].is_empty() => Some(number(col, check_uncertainty)?),
            _ => None,
        };
        let spin = if let Some(cols) = w_cols {
            let mut w = [0.0; 3];
            for (value, col) in w.iter_mut().zip(cols) {
                *value = number(col, |v| {
                    (!(v.is_finite() && v.abs() <= 1e4)).then_some("[-1e4, 1e4] rad/s")
                })?;
            }
            Spin::RadPerSecond(w)
        } else if let Some(col) = spin_col {
            let text = fields[col];
            match spin_name(text) {
                Some(r) => Spin::Ratio(r),
                None if text.is_empty() => Spin::Ratio(0.0),
                None => Spin::Ratio(
                    number(col, |v| {
                        (!(v.is_finite() && v.abs() <= 10.0)).then_some("[-10, 10] (spin ratio)")
                    })
                    .map_err(|_| {
                        InputError(format!(
                        "line {n}: spin '{text}' is not stun, follow, draw or a number (spin ratio)"
                    ))
                    })?,
                ),
            }
        } else {
            Spin::Ratio(0.0)
        };
        out.push(Measurement {
            id: id_col
                .map(|c| fields[c].to_owned())
                .filter(|s| !s.is_empty())
                .unwrap_or_else(|| format!("line {n}")),
            series: series_col
                .map(|c| fields[c].to_owned())
                .filter(|s| !s.is_empty())
                .unwrap_or_else(|| format!("{speed_mps} m/s")),
            cut_deg,
            speed_mps,
            spin,
            throw_deg,
            uncertainty_deg,
        });
    }
    Ok(out)
}
