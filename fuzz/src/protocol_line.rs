//! Target `protocol_line`: the bytes as a serial stream into the firmware's line path,
//! [`LineReader`] → [`Session::serve`], one session per input (so one input can hold
//! several request lines, e.g. the chunks of a stroke).
//!
//! Checked for every line: no panic; never an `internal` (the answer did not fit) or a
//! `numerical_failure` error (the core's guard, which input that passed validation never
//! trips); a blank line gets no answer and any other line exactly one: valid UTF-8, at
//! most [`MAX_ANSWER`] bytes, one `\n` and only at the end; JSON that a host reads back
//! as an [`Answer`] (so no `NaN`/`null` numbers), of the kind `serve` reported (an error
//! of the reported class, or the request's own answer; `shutdown` ends the session and
//! reports the session's counters) — or, for `shot`, a `{"shot":{...}}` object whose
//! only `null`s are its absent parts; no `NaN` or `inf` written out as a word (unless the
//! line itself held one that an error message may echo); and the session's counters
//! equal the lines answered and the errors among them.

use crate::finite::has_word;
use cuesight_protocol::{
    Answer, AnswerLine, Control, ErrorKind, Event, Identity, LineReader, Served, Session,
    MAX_ANSWER, MAX_LINE,
};

/// Who answers, for `version`.
const IDENTITY: Identity = Identity {
    firmware: "cuesight-fuzz",
    board: "fuzz",
};

/// What one input reached (for checking seeds).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Report {
    /// Lines answered.
    pub answers: u32,
    /// Of which errors.
    pub errors: u32,
}

/// Feeds `data` byte by byte through a line reader into a new session, checking every
/// answer (see the module docs). An unterminated last line gets no answer, as on the
/// serial port.
pub fn run(data: &[u8]) -> Report {
    let mut reader = Box::new(LineReader::<MAX_LINE>::new());
    let mut session = Box::new(Session::new(IDENTITY));
    let mut out = AnswerLine::new();
    let mut report = Report::default();
    for &byte in data {
        let Some(event) = reader.push(byte) else {
            continue;
        };
        let line = match &event {
            Event::Line(line) => Some(line.to_vec()),
            Event::Overlong { .. } => None,
        };
        let blank = line
            .as_deref()
            .is_some_and(|l| l.iter().all(|b| matches!(b, b' ' | b'\t')));
        let Some(served) = session.serve(event, &mut out) else {
            assert!(blank, "no answer to {:?}", show(line.as_deref()));
            assert!(out.is_empty(), "no answer, but the buffer holds one");
            continue;
        };
        assert!(!blank, "a blank line was answered");
        report.answers += 1;
        report.errors += u32::from(served.error.is_some());
        assert_eq!(session.requests(), report.answers, "requests counter");
        assert_eq!(session.errors(), report.errors, "errors counter");
        check_answer(line.as_deref(), &out, &served, &session);
    }
    report
}

fn show(line: Option<&[u8]>) -> String {
    line.map_or_else(
        || "an overlong line".into(),
        |l| String::from_utf8_lossy(l).into_owned(),
    )
}

/// One answer line against what `serve` reported.
fn check_answer(line: Option<&[u8]>, out: &[u8], served: &Served, session: &Session) {
    let request = show(line);
    let text = std::str::from_utf8(out)
        .unwrap_or_else(|e| panic!("answer to {request:?} is not UTF-8 ({e}): {out:?}"));
    assert!(
        out.len() <= MAX_ANSWER,
        "answer of {} bytes to {request:?}",
        out.len()
    );
    let Some(json) = text.strip_suffix('\n') else {
        panic!("answer to {request:?} does not end in a newline: {text:?}");
    };
    assert!(
        !json.contains('\n'),
        "answer to {request:?} spans lines: {text:?}"
    );
    assert!(
        !matches!(
            served.error,
            Some(ErrorKind::Internal | ErrorKind::NumericalFailure)
        ),
        "answer to {request:?} is an error that valid or invalid input never causes: {json}"
    );
    let value: serde_json::Value = serde_json::from_str(json)
        .unwrap_or_else(|e| panic!("answer to {request:?} is not JSON ({e}): {json}"));
    let shot = value.get("shot").is_some();
    // serde-json-core writes a non-finite number as `null`; only the shot answer has
    // optional parts, which are `null` when absent.
    let optional: &[&str] = if shot { SHOT_OPTIONAL } else { &[] };
    assert!(
        !has_null(&value, optional),
        "answer to {request:?} has a null (a non-finite number): {json}"
    );
    check_words(line, json, &request);
    if shot {
        // Written directly, not through `Answer` (which has no shot variant).
        assert!(
            value.as_object().is_some_and(|o| o.len() == 1) && value["shot"].is_object(),
            "shot answer {json}"
        );
        assert_eq!(served.request, Some("shot"), "{json} for {served:?}");
        assert_eq!(served.control, Control::Continue);
        return;
    }
    let answer: Answer = serde_json::from_value(value)
        .unwrap_or_else(|e| panic!("answer to {request:?} is not an Answer ({e}): {json}"));
    assert_eq!(
        served.error.is_some(),
        served.request.is_none(),
        "served {served:?}"
    );
    match (&answer, served.error, served.request) {
        (Answer::Error(error), Some(kind), None) => {
            assert_eq!(error.kind, kind, "error class in {json}")
        }
        (Answer::Collide(_), None, Some("collide"))
        | (Answer::Params(_), None, Some("params"))
        | (Answer::Stroke(_) | Answer::StrokeChunk(_), None, Some("stroke"))
        | (Answer::Version(_), None, Some("version")) => {}
        (Answer::Shutdown(counts), None, Some("shutdown")) => {
            assert_eq!(counts.requests, session.requests(), "shutdown's requests");
            assert_eq!(counts.errors, session.errors(), "shutdown's errors");
        }
        _ => panic!("answer {json} to {request:?}, but serve reported {served:?}"),
    }
    assert_eq!(
        served.control == Control::Shutdown,
        matches!(answer, Answer::Shutdown(_)),
        "control {:?} for {json}",
        served.control
    );
}

/// The parts of a shot answer that are `null` when absent.
const SHOT_OPTIONAL: &[&str] = &[
    "solve",
    "contact",
    "object_ball",
    "target",
    "miss",
    "pocket",
    "error_estimate",
];

/// No `NaN` or `inf` written out as a word, unless the line held one (an error message
/// may echo a field name or a value the line gave).
fn check_words(line: Option<&[u8]>, json: &str, request: &str) {
    let echoes = line.is_some_and(|l| {
        let lower = l.to_ascii_lowercase();
        lower.windows(3).any(|w| w == b"nan" || w == b"inf")
    });
    if !echoes {
        for word in ["NaN", "inf"] {
            assert!(
                !has_word(json, word),
                "answer to {request:?} writes out {word}: {json}"
            );
        }
    }
}

/// A `null` anywhere but as the value of a key in `optional`.
fn has_null(value: &serde_json::Value, optional: &[&str]) -> bool {
    match value {
        serde_json::Value::Null => true,
        serde_json::Value::Array(items) => items.iter().any(|v| has_null(v, optional)),
        serde_json::Value::Object(fields) => fields.iter().any(|(key, v)| {
            !(v.is_null() && optional.contains(&key.as_str())) && has_null(v, optional)
        }),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_session_is_answered_line_by_line() {
        let report = run(b"{\"version\":{}}\n\n  \n{\"collide\":{\"speed\":-1,\"cut\":0}}\r\n{\"shutdown\":{}}\n{");
        assert_eq!(
            report,
            Report {
                answers: 3,
                errors: 1
            }
        );
    }
}
