//! The `cuesight` binary's I/O edges, run as a process: every subcommand's output to a
//! full disk (`/dev/full`: one line `error: writing the output: ...`, exit 1) and to a
//! closed pipe (quiet, exit 0), never a panic.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_cuesight");

/// A file under this test's temp directory.
fn temp_file(name: &str, contents: &[u8]) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_io");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, contents).unwrap();
    path
}

fn scene(name: &str) -> String {
    format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn demo_session() -> String {
    format!(
        "{}/../firmware/demo/session.jsonl",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// A small throw file `calibrate` fits in a moment.
fn throw_csv() -> PathBuf {
    let mut csv = String::from("cut_deg,speed_mps,spin,throw_deg\n");
    for (cut, throw) in [(10, 1.9), (20, 2.9), (30, 3.4), (40, 3.5), (50, 3.3)] {
        csv += &format!("{cut},1.5,stun,{throw}\n");
    }
    temp_file("throw.csv", csv.as_bytes())
}

/// Every subcommand (and `--help`), with arguments that succeed and print something.
fn commands() -> Vec<Vec<String>> {
    let throw = throw_csv().to_str().unwrap().to_owned();
    [
        vec!["collide", "--speed", "2", "--cut", "30"],
        vec!["collide", "--speed", "2", "--cut", "30", "--json"],
        vec![
            "collide",
            "--speed",
            "2",
            "--cut",
            "30",
            "--model",
            "reference",
        ],
        vec!["shot", "--scene", &scene("cut_to_corner.toml")],
        vec!["shot", "--scene", &scene("cut_to_corner.toml"), "--json"],
        vec!["calibrate", "--throw", &throw, "--fit", "mu"],
        vec!["calibrate", "--throw", &throw, "--fit", "mu", "--json"],
        vec!["device", "--loopback", "--session", &demo_session()],
        vec![
            "device",
            "--loopback",
            "--session",
            &demo_session(),
            "--json",
        ],
        vec!["--help"],
        vec!["collide", "--help"],
        vec!["--version"],
    ]
    .into_iter()
    .map(|args| args.into_iter().map(str::to_owned).collect())
    .collect()
}

fn run_with_stdout(args: &[String], stdout: Stdio) -> Output {
    Command::new(BIN)
        .args(args)
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .output()
        .expect("run cuesight")
}

#[test]
fn every_command_succeeds_on_a_normal_stdout() {
    for args in commands() {
        let out = run_with_stdout(&args, Stdio::piped());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {stderr}");
        assert!(!out.stdout.is_empty(), "{args:?}");
    }
}

#[test]
fn a_full_disk_is_one_error_line_and_exit_1() {
    if !Path::new("/dev/full").exists() {
        eprintln!("no /dev/full here: skipped");
        return;
    }
    for args in commands() {
        let full = File::options().write(true).open("/dev/full").unwrap();
        let out = run_with_stdout(&args, Stdio::from(full));
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        // The device's console may print notes before the first answer; the error is
        // the last line and the only one of its kind.
        let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
        assert_eq!(errors.len(), 1, "{args:?}: {stderr}");
        assert!(
            errors[0].starts_with("error: writing the output: ")
                && errors[0].contains("No space left on device"),
            "{args:?}: {stderr}"
        );
        if args[0] != "device" {
            assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        }
    }
}

#[test]
fn a_closed_pipe_is_a_quiet_exit_0() {
    for args in commands() {
        let mut child = Command::new(BIN)
            .args(&args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run cuesight");
        // The reader goes away before the command has printed anything.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}: {stderr}");
        if args[0] == "device" {
            // With --json the console's notes (`connected:`, headings) are on stderr.
            assert!(
                !stderr.contains("error") && !stderr.contains("panicked"),
                "{args:?}: {stderr}"
            );
        } else {
            assert!(stderr.is_empty(), "{args:?}: {stderr}");
        }
    }
}

#[test]
fn a_closed_pipe_through_the_shell_is_quiet() {
    // `cuesight ... | head -c0`, as a person types it; the shell reports the first
    // command's status through a file.
    let status = temp_file("pipe-status", b"");
    let script = format!(
        "{{ \"$0\" collide --speed 2 --cut 30; echo $? > '{}'; }} | head -c0",
        status.display()
    );
    let out = Command::new("sh")
        .args(["-c", &script, BIN])
        .stderr(Stdio::piped())
        .output()
        .expect("run sh");
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.is_empty(), "{stderr}");
    assert_eq!(std::fs::read_to_string(&status).unwrap().trim(), "0");
}

#[test]
fn a_full_stderr_is_not_a_panic() {
    if !Path::new("/dev/full").exists() {
        return;
    }
    for (args, code) in [
        (&["collide", "--speed", "x", "--cut", "30"][..], 2),
        (&["collide", "--speed", "0", "--cut", "30"][..], 1),
        (&["shot", "--scene", "/no/such.toml"][..], 2),
        (&["calibrate", "--throw", "/no/such.csv"][..], 1),
        (
            &["device", "--loopback", "--session", "/no/such.jsonl"][..],
            2,
        ),
    ] {
        let full = File::options().write(true).open("/dev/full").unwrap();
        let out = Command::new(BIN)
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::from(full))
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(code), "{args:?}");
    }
}

/// Runs `cuesight args` (stdin from `stdin`), killed after 10 s; the output and how long
/// it took.
fn timed(args: &[&str], stdin: Stdio) -> (Output, std::time::Duration) {
    let started = std::time::Instant::now();
    let mut child = Command::new(BIN)
        .args(args)
        .stdin(stdin)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run cuesight");
    while child.try_wait().unwrap().is_none() {
        if started.elapsed().as_secs() >= 10 {
            child.kill().unwrap();
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let out = child.wait_with_output().unwrap();
    (out, started.elapsed())
}

/// `args` is refused with exit `code` and one stderr error line, `expected`, within a
/// second.
fn refused_quickly(args: &[&str], stdin: Stdio, code: i32, expected: &str) {
    let (out, took) = timed(args, stdin);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "{args:?}: {stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{args:?}: {stderr}");
    assert_eq!(errors[0], expected, "{args:?}");
    assert!(took.as_secs_f64() < 1.0, "{args:?}: {took:?}");
}

/// A link to `/dev/zero` under `name` (the extension picks the format).
#[cfg(unix)]
fn zero(name: &str) -> String {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_io");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    std::os::unix::fs::symlink("/dev/zero", &path).unwrap();
    path.to_str().unwrap().to_owned()
}

#[cfg(unix)]
#[test]
fn endless_input_files_are_refused_within_a_second() {
    const CAP: &str = "larger than 1048576 bytes (1 MiB), refused";
    let scene_file = scene("cut_to_corner.toml");
    let (json, toml) = (zero("zero.json"), zero("zero.toml"));
    let (params, session) = (zero("p.json"), zero("s.jsonl"));
    let (csv, throw_json) = (zero("t.csv"), zero("t.json"));
    let collide = [
        "collide", "--speed", "2", "--cut", "30", "--params", &params,
    ];
    for (args, code, error) in [
        (
            &["shot", "--scene", &json][..],
            2,
            format!("scene file {json}: {CAP}"),
        ),
        (
            &["shot", "--scene", &toml],
            2,
            format!("scene file {toml}: {CAP}"),
        ),
        (
            &["shot", "--scene", &scene_file, "--params", &params],
            2,
            format!("params file {params}: larger than 1 MiB, refused"),
        ),
        (
            &collide,
            2,
            format!("params file {params}: larger than 1 MiB, refused"),
        ),
        (&["calibrate", "--throw", &csv], 1, format!("{csv}: {CAP}")),
        (
            &["calibrate", "--throw", &throw_json],
            1,
            format!("{throw_json}: {CAP}"),
        ),
        (
            &["device", "--loopback", "--session", &session],
            2,
            format!("cannot read {session}: {CAP}"),
        ),
    ] {
        refused_quickly(args, Stdio::null(), code, &format!("error: {error}"));
    }
}

#[cfg(unix)]
#[test]
fn endless_stdin_lines_are_refused_within_a_second() {
    let dev_zero = File::open("/dev/zero").unwrap();
    refused_quickly(
        &["device", "--loopback"],
        Stdio::from(dev_zero),
        2,
        "error: reading the requests: line 1 is longer than 65536 bytes (64 KiB), refused",
    );
}

#[test]
fn a_scene_of_1_mib_is_read_and_one_byte_more_is_refused() {
    let text = std::fs::read_to_string(scene("cut_to_corner.json")).unwrap();
    let limit = 1 << 20;
    let padded = |size: usize| format!("{text}{}", " ".repeat(size - text.len()));
    let at = temp_file("at-limit.json", padded(limit).as_bytes());
    let out = Command::new(BIN)
        .args(["shot", "--json", "--scene", at.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let over = temp_file("over-limit.json", padded(limit + 1).as_bytes());
    let out = Command::new(BIN)
        .args(["shot", "--scene", over.to_str().unwrap()])
        .output()
        .unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(
        stderr.trim_end(),
        format!(
            "error: scene file {}: larger than 1048576 bytes (1 MiB), refused",
            over.display()
        )
    );
}

/// A FIFO fed without end by another thread: the cap ends the read.
#[cfg(unix)]
#[test]
fn a_scene_fifo_without_end_is_refused_within_a_second() {
    use std::io::Write;
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_io");
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("fifo-scene.json");
    let _ = std::fs::remove_file(&fifo);
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("no mkfifo: skipped");
        return;
    }
    let writer_path = fifo.clone();
    let writer = std::thread::spawn(move || {
        let mut pipe = File::options().write(true).open(writer_path).unwrap();
        let block = [b' '; 4096];
        // Until the reader has gone (a broken pipe).
        while pipe.write_all(&block).is_ok() {}
    });
    let shown = fifo.to_str().unwrap();
    refused_quickly(
        &["shot", "--scene", shown],
        Stdio::null(),
        2,
        &format!("error: scene file {shown}: larger than 1048576 bytes (1 MiB), refused"),
    );
    writer.join().unwrap();
}

#[test]
fn console_lines_are_bounded() {
    use cuesight_cli::device::session::{bounded_lines, MAX_LINE_BYTES};
    let lines = |text: &[u8]| -> Vec<Result<String, String>> {
        bounded_lines(text)
            .map(|l| l.map_err(|e| e.to_string()))
            .collect()
    };
    assert_eq!(
        lines(b"a\r\nb\n\nc"),
        ["a", "b", "", "c"].map(|l| Ok(l.to_owned()))
    );
    assert!(lines(b"").is_empty());
    // At the bound, with either line end, or none at the end of the input; then one
    // byte over.
    let at = vec![b'x'; MAX_LINE_BYTES];
    for (end, count) in [(&b"\n"[..], 2), (b"\r\n", 2), (b"", 1)] {
        let next: &[u8] = if end.is_empty() { b"" } else { b"next\n" };
        let got = lines(&[&at[..], end, next].concat());
        assert_eq!(got.len(), count);
        assert_eq!(got[0].as_ref().map(String::len), Ok(MAX_LINE_BYTES));
    }
    let over = [&b"ok\n"[..], &vec![b'x'; MAX_LINE_BYTES + 1], b"\nnext\n"].concat();
    let got = lines(&over);
    assert_eq!(got.len(), 2, "stops at the error");
    assert_eq!(
        got[1],
        Err("line 2 is longer than 65536 bytes (64 KiB), refused".to_owned())
    );
    assert!(lines(b"\xff\n")[0].is_err());
}
