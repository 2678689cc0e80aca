//! The console against an in-process device ([`Loopback`]): sessions, expected and
//! unexpected errors, local JSON errors, the schema check, a closed output.

use std::io::{self, Write};
use std::time::Duration;

use cuesight_link::frame::{self, MAX_FRAME};
use cuesight_link::{LinkError, Response, SCHEMA_HASH};

use super::session::{parse_line, play, Console, DeviceError, Line, Show, Tally};
use super::transport::{Loopback, Transport, TransportError};
use cuesight_host::firmware::Incoming;
use cuesight_host::strokes::{stroke_requests, synthetic_stroke_of};

const TIMEOUT: Duration = Duration::from_secs(1);

/// Plays `session` on a fresh loopback device; the tally and what was printed.
fn play_text(session: &str, show: Show) -> (Tally, String, String) {
    let mut link = Loopback::new();
    let mut console = Console::connect(&mut link, TIMEOUT).expect("connects");
    let (mut out, mut notes) = (Vec::new(), Vec::new());
    let tally = play(&mut console, session.as_bytes(), &mut out, &mut notes, show).expect("plays");
    (
        tally,
        String::from_utf8(out).unwrap(),
        String::from_utf8(notes).unwrap(),
    )
}

const ECHO: Show = Show {
    json: false,
    echo: true,
    lenient: false,
};

#[test]
fn session_lines() {
    assert_eq!(parse_line("  "), Line::Skip);
    assert_eq!(parse_line("## a comment"), Line::Skip);
    assert_eq!(parse_line("# Heading "), Line::Heading("Heading"));
    assert_eq!(
        parse_line("{\"version\":{}}"),
        Line::Request {
            json: "{\"version\":{}}",
            expect_error: false
        }
    );
    assert_eq!(
        parse_line("!expect-error {\"version\":{}}"),
        Line::Request {
            json: "{\"version\":{}}",
            expect_error: true
        }
    );
}

#[test]
fn a_session_with_every_request_kind_passes() {
    let stroke = synthetic_stroke_of(7, 3333.0, 2.5, Some(cuesight_link::STROKE_CAPACITY));
    let mut session = String::from(
        "# heading\n## comment\n{\"version\":{}}\n\
         {\"collide\":{\"speed\":2,\"cut\":30,\"spin\":[0,40,0],\"mu\":0.06}}\n\
         {\"params\":{\"mu\":0.06}}\n{\"params\":{}}\n\
         !expect-error {\"collide\":{\"speed\":-1,\"cut\":30}}\n",
    );
    for request in stroke_requests(&stroke, 125) {
        session.push_str(&serde_json::to_string(&request).unwrap());
        session.push('\n');
    }
    session.push_str(
        "{\"shot\":{\"table\":\"pool\",\"cue\":[0.635,0.635],\"balls\":[[1.9,0.9]],\
         \"speed\":3.0,\"tip\":[0.0,0.2],\"pocket\":3,\"model\":\"auto\"}}\n\
         {\"shutdown\":{}}\n",
    );
    let (tally, out, notes) = play_text(&session, ECHO);
    assert!(tally.passed(), "{tally:?}\n{out}\n{notes}");
    assert_eq!(tally.sent, 5 + 40 + 2, "{out}");
    assert_eq!(tally.expected_errors, 1);
    assert!(tally.shut_down);
    assert!(out.contains("\n== heading\n"), "{out}");
    assert!(!out.contains("comment"), "{out}");
    assert!(
        out.contains("< error: speed = -1 is outside (0, 100] m/s"),
        "{out}"
    );
    assert!(
        out.contains("stroke 1: 39 of 40 chunks held, 4875 samples"),
        "{out}"
    );
    assert!(
        out.contains("< stroke 1: cue ") && out.contains("(5000 samples"),
        "{out}"
    );
    assert!(out.contains("< solved: aim "), "{out}");
    assert!(
        out.contains("< session over: 48 requests answered, 1 with an error"),
        "{out}"
    );
    assert!(notes.is_empty(), "{notes}");
}

#[test]
fn unexpected_errors_fail_after_the_whole_session() {
    let session = "{\"collide\":{\"speed\":-1,\"cut\":30}}\n\
                   !expect-error {\"collide\":{\"speed\":2,\"cut\":30}}\n\
                   {\"collide\":{\"speed\":2,\"cut\":NaN}}\n\
                   !expect-error {\"collide\":{\"speed\":2,\"cut\":30,\"spinn\":[0,0,0]}}\n\
                   {\"collide\":{\"speed\":2,\"cut\":30,\"model\":\"reference\"}}\n\
                   {\"params\":{}}\n";
    let (tally, out, _) = play_text(session, ECHO);
    let lines: Vec<usize> = tally.unexpected.iter().map(|u| u.line).collect();
    assert_eq!(lines, [1, 2, 3, 5], "{tally:?}");
    assert_eq!(tally.expected_errors, 1);
    // The lines that are no request were not sent.
    assert_eq!(tally.sent, 4);
    assert!(tally.unexpected[1]
        .problem
        .starts_with("an error was expected"));
    assert!(
        tally.unexpected[2].problem.contains("line 1 column"),
        "serde_json's message: {:?}",
        tally.unexpected[2]
    );
    assert!(
        out.contains("! line 4: not a request, not sent: unknown field `spinn`"),
        "{out}"
    );
    assert!(tally.unexpected[3]
        .problem
        .contains("runs on the host only"));
    assert!(
        out.contains("< defaults now: model kim-grip, mu 0.05"),
        "{out}"
    );
}

#[test]
fn a_person_typing_is_not_failed_by_errors() {
    let show = Show {
        lenient: true,
        echo: false,
        json: false,
    };
    let (tally, out, _) = play_text("{\"collide\":{\"speed\":-1,\"cut\":30}}\nnonsense\n", show);
    assert!(tally.passed());
    assert!(!out.contains("> "), "no echo: {out}");
}

#[test]
fn json_mode_prints_one_answer_per_request() {
    let show = Show {
        json: true,
        echo: true,
        lenient: false,
    };
    let (tally, out, notes) = play_text(
        "# h\n{\"params\":{}}\n{\"collide\":{\"speed\":2,\"cut\":30}}\nbad\n",
        show,
    );
    assert_eq!(tally.sent, 2);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    let params: Response = serde_json::from_str(lines[0]).unwrap();
    assert!(matches!(params, Response::Params(_)));
    let collide: serde_json::Value = serde_json::from_str(lines[1]).unwrap();
    assert_eq!(collide["collide"]["model"], "kim-grip");
    assert!(
        notes.contains("== h") && notes.contains("! line 4"),
        "{notes}"
    );
}

#[test]
fn requests_after_shutdown_are_not_sent() {
    let (tally, _, notes) = play_text("{\"shutdown\":{}}\n{\"version\":{}}\n", ECHO);
    assert!(tally.shut_down);
    assert_eq!(tally.sent, 1);
    assert_eq!(tally.unexpected.len(), 1);
    assert!(notes.contains("line 2: not sent"), "{notes}");
}

#[test]
fn frames_are_numbered_from_zero() {
    let mut link = Loopback::new();
    let mut console = Console::connect(&mut link, TIMEOUT).unwrap();
    assert_eq!(console.next_seq(), 1, "version went out as frame 0");
    let _ = play(
        &mut console,
        "{\"params\":{}}\nbad\n{\"params\":{}}\n".as_bytes(),
        &mut io::sink(),
        &mut io::sink(),
        ECHO,
    )
    .unwrap();
    assert_eq!(console.next_seq(), 3);
    assert_eq!(link.counts(), (3, 0), "the device saw no sequence error");
}

/// A device of another schema: every frame is answered with its refusal, in its schema.
struct Foreign;

const FOREIGN: u32 = 0x1234_abcd;

impl Transport for Foreign {
    fn send(&mut self, _: &[u8]) -> Result<(), TransportError> {
        Ok(())
    }

    fn next_frame(&mut self, _: Duration) -> Result<Incoming, TransportError> {
        let refusal = Response::Error(LinkError::SchemaMismatch {
            device: FOREIGN,
            host: SCHEMA_HASH,
        });
        let mut wire = [0u8; MAX_FRAME];
        let len = frame::encode(FOREIGN, 0, &refusal, &mut wire).unwrap();
        let mut raw = [0u8; MAX_FRAME];
        let n = cobs::decode(&wire[..len - 1], &mut raw).unwrap();
        Ok(Incoming::Frame(raw[..n].to_vec()))
    }
}

#[test]
fn a_foreign_schema_is_named_at_connect() {
    let Err(error) = Console::connect(Foreign, TIMEOUT) else {
        panic!("connected to a foreign schema")
    };
    assert!(matches!(error, DeviceError::Schema { device: FOREIGN }));
    assert_eq!(
        error.to_string(),
        format!("device speaks schema 0x1234abcd, this host {SCHEMA_HASH:#010x}")
    );
    assert_eq!(super::exit_code(&error), super::EXIT_SCHEMA);
}

/// A device that never answers.
struct Silent;

impl Transport for Silent {
    fn send(&mut self, _: &[u8]) -> Result<(), TransportError> {
        Ok(())
    }

    fn next_frame(&mut self, timeout: Duration) -> Result<Incoming, TransportError> {
        Err(TransportError::Timeout(timeout))
    }
}

#[test]
fn silence_is_a_link_error() {
    let Err(error) = Console::connect(Silent, TIMEOUT) else {
        panic!("connected to nothing")
    };
    assert!(matches!(
        error,
        DeviceError::Transport(TransportError::Timeout(_))
    ));
    assert_eq!(super::exit_code(&error), super::EXIT_LINK);
}

/// An output whose reader went away.
struct ClosedPipe;

impl Write for ClosedPipe {
    fn write(&mut self, _: &[u8]) -> io::Result<usize> {
        Err(io::ErrorKind::BrokenPipe.into())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

#[test]
fn a_closed_output_is_an_error_not_a_panic() {
    let mut link = Loopback::new();
    let mut console = Console::connect(&mut link, TIMEOUT).unwrap();
    let result = play(
        &mut console,
        "{\"params\":{}}\n".as_bytes(),
        &mut ClosedPipe,
        &mut io::sink(),
        ECHO,
    );
    assert!(matches!(result, Err(DeviceError::Output(_))));
}

/// The demo session `cargo xtask run` plays passes on the in-process device too.
#[test]
fn the_demo_session_passes_on_the_loopback() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../firmware/demo/session.jsonl"
    );
    let session = std::fs::read_to_string(path).unwrap();
    let (tally, out, notes) = play_text(&session, ECHO);
    assert!(tally.passed(), "{tally:?}\n{out}\n{notes}");
    assert!(tally.shut_down);
    assert!(tally.expected_errors >= 3, "{tally:?}");
    for kind in ["version", "collide", "params", "stroke", "shot", "shutdown"] {
        assert!(
            session.contains(&format!("{{\"{kind}\":")),
            "the demo shows {kind}"
        );
    }
    assert!(
        out.contains("stroke 1: cue "),
        "the full window is estimated: {out}"
    );
}

/// Serves a [`Loopback`] device on a local TCP socket, as QEMU's `-serial tcp::PORT,server`
/// would serve the firmware; `prefix` is written first (junk before the hello).
fn tcp_device(prefix: Vec<u8>) -> std::net::SocketAddr {
    use std::io::Read;
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap();
    std::thread::spawn(move || {
        let (mut socket, _) = listener.accept().unwrap();
        let mut device = Loopback::new();
        let mut buf = [0u8; 512];
        socket.write_all(&prefix).unwrap();
        loop {
            loop {
                match device.next_frame(Duration::ZERO) {
                    Ok(Incoming::Frame(raw)) => {
                        if socket
                            .write_all(&cuesight_host::firmware::cobs_frame(&raw))
                            .is_err()
                        {
                            return;
                        }
                    }
                    Ok(Incoming::Fault(_)) => {}
                    // Shut down: close the socket.
                    Err(TransportError::Closed) => return,
                    Err(_) => break,
                }
            }
            match socket.read(&mut buf) {
                Ok(0) | Err(_) => return,
                Ok(n) => {
                    if device.send(&buf[..n]).is_err() {
                        return;
                    }
                }
            }
        }
    });
    address
}

#[test]
fn a_device_holding_junk_still_connects() {
    let mut link = Loopback::new();
    // Half a frame: the console's leading zero ends it, the device answers it unnumbered.
    link.send(&[5, 1, 2]).unwrap();
    let mut console = Console::connect(&mut link, TIMEOUT).unwrap();
    assert_eq!(console.version().schema, SCHEMA_HASH);
    assert_eq!(console.take_notes().len(), 1, "the skipped answer is noted");
    assert_eq!(link.counts(), (2, 1));
}

#[test]
fn a_tcp_stream_carries_a_session() {
    use super::transport::Stream;
    // An oversized frame of junk first: cut at MAX_RAW, reported, skipped.
    let mut junk = vec![7u8; 3000];
    junk.push(0);
    let address = tcp_device(junk);
    let mut link = Stream::tcp(&address.to_string()).unwrap();
    let first = link.next_frame(TIMEOUT).unwrap();
    assert!(
        matches!(
            first,
            Incoming::Fault(cuesight_link::error::FrameFault::Oversized { length: 3000 })
        ),
        "{first:?}"
    );
    let mut console = Console::connect(&mut link, TIMEOUT).unwrap();
    let (mut out, mut notes) = (Vec::new(), Vec::new());
    let tally = play(
        &mut console,
        "{\"collide\":{\"speed\":2,\"cut\":30}}\n{\"shutdown\":{}}\n".as_bytes(),
        &mut out,
        &mut notes,
        ECHO,
    )
    .unwrap();
    let out = String::from_utf8(out).unwrap();
    assert!(tally.passed() && tally.shut_down, "{tally:?} {out}");
    assert!(out.contains("< kim-grip sliding: "), "{out}");
    // The device closed after shutdown.
    assert!(matches!(
        link.next_frame(TIMEOUT),
        Err(TransportError::Closed)
    ));
}
