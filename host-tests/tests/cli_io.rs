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
