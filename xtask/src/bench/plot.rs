//! `docs/tradeoff.svg`: the Pareto plot of the trade, error against instructions,
//! log–log, drawn from `tradeoff.json` with plotters' SVG backend.

use plotters::prelude::*;
use serde_json::Value;

use crate::cmd::{Failure, Result};

/// One measured configuration.
struct Point {
    label: String,
    precision: String,
    backend: String,
    instructions: f64,
    /// Max |Δv|/U over the grid, in %.
    error: f64,
}

const F32: RGBColor = RGBColor(31, 119, 180);
const F64: RGBColor = RGBColor(214, 39, 40);
const MICROMATH: RGBColor = RGBColor(44, 160, 44);
const TARGET: RGBColor = RGBColor(150, 150, 150);

/// Targets drawn on the plot (issue 4).
const KIM_GRIP_TARGET: f64 = 150.0;
const EXACT_TARGET: f64 = 20_000.0;
const EXACT_ACCURACY_PERCENT: f64 = 0.02;

fn points(report: &Value) -> Vec<Point> {
    report["rows"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|row| {
            Some(Point {
                label: row["model"].as_str()?.to_string(),
                precision: row["precision"].as_str()?.to_string(),
                backend: row["backend"].as_str()?.to_string(),
                instructions: row["instructions"]["release"]["mean"].as_f64()?,
                error: 100.0 * row["error"]["all"]["max"]["velocity"].as_f64()?,
            })
        })
        .filter(|p| p.instructions > 0.0 && p.error > 0.0)
        .collect()
}

/// Decades covering `values`.
fn decades(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil()),
    )
}

/// Points no other point beats in both instructions and error, cheapest first.
fn pareto(points: &[Point]) -> Vec<(f64, f64)> {
    let mut sorted: Vec<(f64, f64)> = points.iter().map(|p| (p.instructions, p.error)).collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for (x, y) in sorted {
        if front.last().is_none_or(|&(_, best)| y < best) {
            front.push((x, y));
        }
    }
    front
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

fn failure<E: std::fmt::Debug>(e: E) -> Failure {
    Failure::new(format!("drawing tradeoff.svg: {e:?}"))
}

/// The SVG document.
pub fn svg(report: &Value) -> Result<String> {
    let points = points(report);
    if points.is_empty() {
        return Err(Failure::new("no point to plot in tradeoff.json"));
    }
    let counted = report["grid"]["counted"].as_u64().unwrap_or(0);
    let scenes = report["grid"]["scenes"].as_u64().unwrap_or(0);
    let (x0, x1) = decades(
        points
            .iter()
            .map(|p| p.instructions)
            .chain([KIM_GRIP_TARGET, EXACT_TARGET]),
    );
    let (y0, y1) = decades(
        points
            .iter()
            .map(|p| p.error)
            .chain([EXACT_ACCURACY_PERCENT]),
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(failure)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "cuesight: accuracy against cost on the Cortex-M4F",
                ("sans-serif", 22),
            )
            .margin(16)
            .margin_right(48)
            .x_label_area_size(56)
            .y_label_area_size(88)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(failure)?;
        chart
            .configure_mesh()
            .x_desc(format!(
                "instructions per prediction (QEMU -icount, opt-level 3, mean of {counted} scenes)"
            ))
            .y_desc(format!("max |Δv|/U on the {scenes}-scene grid (%)"))
            .x_label_formatter(&|x| super::report::thousands(*x))
            .y_label_formatter(&|y| super::report::sig3(*y))
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(failure)?;
        draw_targets(&mut chart, (x0, x1), (y0, y1))?;
        draw_points(&mut chart, &points)?;
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK.mix(0.3))
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(failure)?;
        root.present().map_err(failure)?;
    }
    Ok(svg)
}

fn draw_targets(chart: &mut Chart, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> Result {
    let style = ShapeStyle::from(&TARGET).stroke_width(1);
    for (x, text) in [
        (KIM_GRIP_TARGET, "KimGrip target 150"),
        (EXACT_TARGET, "Exact target 20,000"),
    ] {
        chart
            .draw_series(LineSeries::new([(x, y0), (x, y1)], style))
            .map_err(failure)?;
        chart
            .draw_series([Text::new(
                text.to_string(),
                (x * 1.05, y1 / 1.6),
                ("sans-serif", 12).into_font().color(&TARGET),
            )])
            .map_err(failure)?;
    }
    chart
        .draw_series(LineSeries::new(
            [(x0, EXACT_ACCURACY_PERCENT), (x1, EXACT_ACCURACY_PERCENT)],
            style,
        ))
        .map_err(failure)?;
    chart
        .draw_series([Text::new(
            "Exact accuracy target 0.02 %".to_string(),
            (x0 * 1.1, EXACT_ACCURACY_PERCENT * 1.15),
            ("sans-serif", 12).into_font().color(&TARGET),
        )])
        .map_err(failure)?;
    Ok(())
}

/// Offsets (px, from the point to the label's top-left corner) that keep every label
/// clear of the others and of every point: for each point, cheapest first, the first of
/// eight places around it whose box (12 px sans-serif: about 7 px a character, 14 px
/// high) overlaps no label placed before and no point's marker.
fn label_offsets(chart: &Chart, points: &[&Point]) -> Vec<(i32, i32)> {
    type Box = (i32, i32, i32, i32); // left, top, right, bottom
    let overlaps = |a: Box, b: Box| a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3;
    let at: Vec<(i32, i32)> = points
        .iter()
        .map(|p| chart.backend_coord(&(p.instructions, p.error)))
        .collect();
    let markers: Vec<Box> = at
        .iter()
        .map(|&(x, y)| (x - 9, y - 9, x + 9, y + 9))
        .collect();
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].instructions.total_cmp(&points[b].instructions));
    let mut placed: Vec<Box> = Vec::new();
    let mut offsets = vec![(7, -14); points.len()];
    for i in order {
        let (x, y) = at[i];
        let (w, h) = (7 * points[i].label.chars().count() as i32, 14);
        let candidates = [
            (7, -14),
            (7, 2),
            (-w - 7, -14),
            (-w - 7, 2),
            (-w / 2, -h - 10),
            (-w / 2, 10),
            (12, -h / 2),
            (-w - 12, -h / 2),
        ];
        let clear = |&(dx, dy): &(i32, i32)| {
            let b = (x + dx, y + dy, x + dx + w, y + dy + h);
            !placed.iter().any(|&p| overlaps(b, p)) && !markers.iter().any(|&m| overlaps(b, m))
        };
        let offset = candidates
            .iter()
            .copied()
            .find(clear)
            .unwrap_or(candidates[0]);
        placed.push((
            x + offset.0,
            y + offset.1,
            x + offset.0 + w,
            y + offset.1 + h,
        ));
        offsets[i] = offset;
    }
    offsets
}

fn draw_points(chart: &mut Chart, points: &[Point]) -> Result {
    // The Pareto front as a staircase.
    let front = pareto(points);
    let mut stairs = Vec::new();
    for (i, &(x, y)) in front.iter().enumerate() {
        if i > 0 {
            stairs.push((x, front[i - 1].1));
        }
        stairs.push((x, y));
    }
    chart
        .draw_series(LineSeries::new(stairs, BLACK.mix(0.35).stroke_width(2)))
        .map_err(failure)?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.mix(0.35).stroke_width(2)));

    let libm = |precision: &'static str| {
        points
            .iter()
            .filter(move |p| p.backend == "libm" && p.precision == precision)
    };
    let labelled: Vec<&Point> = libm("f32").chain(libm("f64")).collect();
    let offsets = label_offsets(chart, &labelled);
    for (precision, color) in [("f32", F32), ("f64", F64)] {
        chart
            .draw_series(
                labelled
                    .iter()
                    .zip(&offsets)
                    .filter(|(p, _)| p.precision == precision)
                    .map(|(p, &offset)| {
                        EmptyElement::at((p.instructions, p.error))
                            + Circle::new((0, 0), 5, color.filled())
                            + Text::new(p.label.clone(), offset, ("sans-serif", 12).into_font())
                    }),
            )
            .map_err(failure)?
            .label(format!("{precision}, libm"))
            .legend(move |(x, y)| Circle::new((x + 9, y), 5, color.filled()));
    }
    chart
        .draw_series(
            points
                .iter()
                .filter(|p| p.backend == "micromath")
                .map(|p| Circle::new((p.instructions, p.error), 9, MICROMATH.stroke_width(2))),
        )
        .map_err(failure)?
        .label("micromath (f32)")
        .legend(|(x, y)| Circle::new((x + 9, y), 6, MICROMATH.stroke_width(2)));
    Ok(())
}
