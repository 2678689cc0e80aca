//! The trace format and its streaming parser (`sensors/src/trace.rs`): every error class
//! with its line and column, line ends, limits, byte-at-a-time use, and the shipped
//! example traces against their truth files (through the streaming estimator). Expected values are written out here or
//! come from the samples the tests format themselves.

use cuesight_sensors::trace::{
    parse_trace, TraceError, TraceParser, TraceSample, HEADER, MAX_LINE_LEN,
};
use cuesight_sensors::{StreamConfig, StreamEvent, StreamFault, StreamingEstimator};

/// Feed `text` one byte at a time, then `finish`; every sample and error in order.
fn run(text: &[u8]) -> Vec<Result<TraceSample, TraceError>> {
    let mut parser = TraceParser::new();
    let mut out = Vec::new();
    for &b in text {
        match parser.push(b) {
            Ok(Some(s)) => out.push(Ok(s)),
            Ok(None) => {}
            Err(e) => out.push(Err(e)),
        }
    }
    match parser.finish() {
        Ok(Some(s)) => out.push(Ok(s)),
        Ok(None) => {}
        Err(e) => out.push(Err(e)),
    }
    out
}

fn csv(samples: &[TraceSample]) -> String {
    let mut text = format!("{HEADER}\n");
    for s in samples {
        let fields: Vec<String> = s.iter().map(|v| v.to_string()).collect();
        text.push_str(&fields.join(","));
        text.push('\n');
    }
    text
}

#[test]
fn samples_round_trip_in_order() {
    let samples: Vec<TraceSample> = vec![
        [0, 0, 0, 0, 0, 0],
        [-32768, 32767, -1, 1, 2049, -2049],
        [123, -456, 7890, -32768, 32767, 0],
    ];
    let text = csv(&samples);
    let parsed: Vec<TraceSample> = run(text.as_bytes())
        .into_iter()
        .map(|r| r.unwrap())
        .collect();
    assert_eq!(parsed, samples);
    // parse_trace gives the same, with 0-based indices.
    let mut seen = Vec::new();
    let n = parse_trace(text.as_bytes(), |i, s| seen.push((i, s))).unwrap();
    assert_eq!(n, 3);
    assert_eq!(
        seen,
        vec![(0, samples[0]), (1, samples[1]), (2, samples[2])]
    );
}

#[test]
fn line_ends_signs_and_leading_zeros() {
    // CRLF, a missing final newline, '+' and leading zeros.
    let text = b"ax,ay,az,gx,gy,gz\r\n+1,-0,007,-00032768,+32767,0\r\n4,5,6,7,8,9";
    assert_eq!(
        run(text),
        vec![Ok([1, 0, 7, -32768, 32767, 0]), Ok([4, 5, 6, 7, 8, 9])]
    );
    // A header alone is an empty trace.
    assert_eq!(parse_trace(b"ax,ay,az,gx,gy,gz\n", |_, _| {}), Ok(0));
    assert_eq!(parse_trace(b"ax,ay,az,gx,gy,gz", |_, _| {}), Ok(0));
}

#[test]
fn a_bad_header_is_named_and_checked_again_on_the_next_line() {
    for header in [
        "ax,ay,az,gx,gy",
        "AX,AY,AZ,GX,GY,GZ",
        " ax,ay,az,gx,gy,gz",
        "ax,ay,az,gx,gy,gz,",
        "gx,gy,gz,ax,ay,az",
        "1,2,3,4,5,6",
        "",
    ] {
        let text = format!("{header}\n1,2,3,4,5,6\n");
        assert_eq!(
            run(text.as_bytes()),
            vec![
                Err(TraceError::BadHeader { line: 1 }),
                Err(TraceError::BadHeader { line: 2 }),
                Err(TraceError::MissingHeader),
            ],
            "{header:?}"
        );
    }
    // A late header is accepted, and the samples after it count from 0.
    let text = b"junk\nax,ay,az,gx,gy,gz\n1,2,3,4,5,6\n";
    assert_eq!(
        run(text),
        vec![
            Err(TraceError::BadHeader { line: 1 }),
            Ok([1, 2, 3, 4, 5, 6])
        ]
    );
    assert_eq!(run(b""), vec![Err(TraceError::MissingHeader)]);
}

#[test]
fn a_wrong_field_count_is_named_with_the_count() {
    for (row, found) in [
        ("1,2,3,4,5", 5),
        ("1,2,3,4,5,6,7", 7),
        ("1", 1),
        ("", 0),
        ("\r", 0),
        (",,,,,,,,,", 10),
    ] {
        let text = format!("{HEADER}\n1,2,3,4,5,6\n{row}\n7,8,9,10,11,12\n");
        assert_eq!(
            run(text.as_bytes()),
            vec![
                Ok([1, 2, 3, 4, 5, 6]),
                Err(TraceError::FieldCount { line: 3, found }),
                Ok([7, 8, 9, 10, 11, 12]),
            ],
            "{row:?}"
        );
    }
}

#[test]
fn a_non_integer_is_named_with_its_line_and_column() {
    for (row, column) in [
        ("x,2,3,4,5,6", 0),
        ("1,,3,4,5,6", 1),
        ("1,2,3.5,4,5,6", 2),
        ("1,2,3,-,5,6", 3),
        ("1,2,3,4, 5,6", 4),
        ("1,2,3,4,5,6 ", 5),
        ("1,2,3,4,5,0x10", 5),
        ("1,2,3,4,--5,6", 4),
        ("1,2,3,4,5,1e3", 5),
        ("1,2\r,3,4,5,6", 1),
    ] {
        let text = format!("{HEADER}\n{row}\n");
        assert_eq!(
            run(text.as_bytes()),
            vec![Err(TraceError::NotInteger { line: 2, column })],
            "{row:?}"
        );
    }
}

#[test]
fn an_out_of_range_value_is_named_with_its_line_and_column() {
    for (row, column) in [
        ("32768,0,0,0,0,0", 0),
        ("0,-32769,0,0,0,0", 1),
        ("0,0,99999999999999999999999,0,0,0", 2),
        ("0,0,0,0,0,+40000", 5),
    ] {
        let text = format!("{HEADER}\n0,0,0,0,0,0\n0,0,0,0,0,0\n{row}\n");
        let out = run(text.as_bytes());
        assert_eq!(
            out[2],
            Err(TraceError::OutOfRange { line: 4, column }),
            "{row:?}"
        );
    }
    // The first bad field of a line is the one named.
    let text = format!("{HEADER}\n1,x,99999,4,5,6\n");
    assert_eq!(
        run(text.as_bytes()),
        vec![Err(TraceError::NotInteger { line: 2, column: 1 })]
    );
}

#[test]
fn line_length_is_bounded() {
    // Exactly MAX_LINE_LEN bytes (leading zeros), with and without CR: taken.
    let first = format!("{:0>width$}", 5, width = MAX_LINE_LEN - 10);
    let row = format!("{first},1,2,3,4,5");
    assert_eq!(row.len(), MAX_LINE_LEN);
    for end in ["\n", "\r\n"] {
        let text = format!("{HEADER}\n{row}{end}9,9,9,9,9,9\n");
        assert_eq!(
            run(text.as_bytes()),
            vec![Ok([5, 1, 2, 3, 4, 5]), Ok([9; 6])],
            "{end:?}"
        );
    }
    // One byte more: reported at that byte, the rest of the line skipped, then on.
    let long = format!("0{row}");
    let text = format!("{HEADER}\n{long}\n9,9,9,9,9,9\n");
    let mut parser = TraceParser::new();
    let mut errors = Vec::new();
    let mut samples = Vec::new();
    for (i, &b) in text.as_bytes().iter().enumerate() {
        match parser.push(b) {
            Err(e) => errors.push((i, e)),
            Ok(Some(s)) => samples.push(s),
            Ok(None) => {}
        }
    }
    let at = HEADER.len() + 1 + MAX_LINE_LEN;
    assert_eq!(errors, vec![(at, TraceError::LineTooLong { line: 2 })]);
    assert_eq!(samples, vec![[9; 6]]);
    assert_eq!(parser.finish(), Ok(None));
    // A very long header line likewise, and its skipped rest is not a header.
    let text = format!("{}\n{HEADER}\n1,1,1,1,1,1", "a".repeat(1000));
    assert_eq!(
        run(text.as_bytes()),
        vec![Err(TraceError::LineTooLong { line: 1 }), Ok([1; 6])]
    );
}

#[test]
fn counters_and_finish_reset() {
    let mut parser = TraceParser::new();
    assert_eq!(
        (parser.line(), parser.samples(), parser.header_seen()),
        (1, 0, false)
    );
    for &b in format!("{HEADER}\n1,2,3,4,5,6\n").as_bytes() {
        parser.push(b).unwrap();
    }
    assert_eq!(
        (parser.line(), parser.samples(), parser.header_seen()),
        (3, 1, true)
    );
    assert_eq!(parser.finish(), Ok(None));
    // Ready for another trace: a sample line is now a bad header.
    for &b in b"1,2,3,4,5,6" {
        parser.push(b).unwrap();
    }
    assert_eq!(parser.push(b'\n'), Err(TraceError::BadHeader { line: 1 }));
}

#[test]
fn errors_name_line_and_column_in_their_messages() {
    let cases = [
        (
            TraceError::BadHeader { line: 1 },
            "line 1: header is not ax,ay,az,gx,gy,gz",
        ),
        (
            TraceError::FieldCount { line: 9, found: 5 },
            "line 9: 5 fields, expected 6 (ax,ay,az,gx,gy,gz)",
        ),
        (
            TraceError::NotInteger { line: 3, column: 4 },
            "line 3, gy: not an integer",
        ),
        (
            TraceError::OutOfRange { line: 7, column: 0 },
            "line 7, ax: outside the i16 range -32768..=32767",
        ),
        (
            TraceError::LineTooLong { line: 2 },
            "line 2: longer than 64 bytes",
        ),
        (
            TraceError::MissingHeader,
            "no header line (ax,ay,az,gx,gy,gz)",
        ),
    ];
    for (error, message) in cases {
        assert_eq!(error.to_string(), message);
    }
}

/// A number after `"key":` in a JSON text, if any (the truth files are flat enough).
fn json_number(text: &str, key: &str) -> Option<f64> {
    let rest = text.split(&format!("\"{key}\":")).nth(1)?;
    let end = rest.find([',', '}', '\n']).unwrap_or(rest.len());
    rest[..end].trim().parse().ok()
}

/// The shipped traces (`firmware/traces/*.csv`) parse whole, with the sample count of
/// their truth files, and the streaming estimator reading `ax` and `gy` finds in them
/// what the truth says: each stroke within 2 samples of its first contact sample and
/// within 1 % of its cue speed (1.5 % at 3333 Hz, where docs/sensors.md §3 gives
/// 0.95 % for the windowed estimator), a double hit as the stroke then `DoubleHit`, a
/// saturated stroke as `Saturated` at its first rail sample.
#[test]
fn shipped_traces_hold_what_their_truth_files_say() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../firmware/traces");
    let mut checked = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("csv") {
            continue;
        }
        let truth = std::fs::read_to_string(path.with_extension("truth.json")).unwrap();
        let odr = json_number(&truth, "odr_hz").unwrap();
        let bound = if odr > 5000.0 { 0.01 } else { 0.015 };
        let mut samples = Vec::new();
        let count = parse_trace(&std::fs::read(&path).unwrap(), |_, s| samples.push(s)).unwrap();
        assert_eq!(
            Some(f64::from(count)),
            json_number(&truth, "samples"),
            "{path:?}"
        );

        let mut est = StreamingEstimator::new(&StreamConfig::new(odr as f32)).unwrap();
        let mut events: Vec<StreamEvent> = samples
            .iter()
            .filter_map(|s| est.push_raw(s[0], Some(s[4])))
            .collect();
        events.extend(est.finish());
        let mut events = events.into_iter();
        let strokes: Vec<&str> = truth.split("\"stroke\":").skip(1).collect();
        assert!(strokes.len() >= 3, "{path:?}");
        for block in strokes {
            let impact = json_number(block, "impact_sample").unwrap() as i64;
            let speed = json_number(block, "cue_speed_mps").unwrap();
            let event = events.next();
            if let Some(at) = json_number(block, "saturated_from_sample") {
                let Some(StreamEvent::Fault(StreamFault::Saturated { index, .. })) = event else {
                    panic!("{path:?}: {event:?} for a saturated stroke");
                };
                assert_eq!(index as f64, at);
                continue;
            }
            let Some(StreamEvent::Stroke(s)) = event else {
                panic!("{path:?}: {event:?} for stroke {block}");
            };
            let error = (f64::from(s.cue_speed) - speed) / speed;
            assert!(
                (s.impact_index as i64 - impact).abs() <= 2 && error.abs() <= bound,
                "{path:?}: {s:?} vs {block}"
            );
            if let Some(second) = json_number(block, "second_impact_sample") {
                let next = events.next();
                let Some(StreamEvent::Fault(StreamFault::DoubleHit { second: found, .. })) = next
                else {
                    panic!("{path:?}: {next:?} after a double hit");
                };
                assert!((found as f64 - second).abs() <= 4.0, "{found} vs {second}");
            }
            checked += 1;
        }
        assert_eq!(events.next(), None, "{path:?}: an event no stroke explains");
    }
    assert!(checked >= 8, "{checked} strokes checked in {dir}");
}

/// The parser's state is its line buffer and a few counters: 88 bytes on a 64-bit host
/// (80 on the 32-bit target, where `usize` is 4 bytes), as its docs say.
#[test]
fn the_parser_is_a_line_buffer_and_counters() {
    let expected = MAX_LINE_LEN + 1 + 2 + 2 * 4 + std::mem::size_of::<usize>();
    let size = std::mem::size_of::<TraceParser>();
    assert!(
        size >= expected && size <= expected.next_multiple_of(8),
        "{size} vs {expected}"
    );
    assert_eq!(
        size,
        if cfg!(target_pointer_width = "64") {
            88
        } else {
            80
        }
    );
}
