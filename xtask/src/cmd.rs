//! Running external commands: echo them, run them, turn a failure into a [`Failure`].

use std::cell::RefCell;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus};

thread_local! {
    /// Where [`run`] sends a command's echo and output on this thread instead of this
    /// process's stderr (`None`: stderr). Set by [`logging_to`].
    static LOG: RefCell<Option<File>> = const { RefCell::new(None) };
}

/// Runs `body` with every [`run`] it makes on this thread echoing to, and sending the
/// command's output to, `log`: for work on a thread of its own (`cargo xtask test`'s
/// installs) whose output would otherwise cut into the steps' log.
pub fn logging_to<T>(log: File, body: impl FnOnce() -> T) -> T {
    LOG.with(|slot| *slot.borrow_mut() = Some(log));
    let result = body();
    LOG.with(|slot| *slot.borrow_mut() = None);
    result
}

/// A handle on this thread's log file, if [`logging_to`] set one.
fn thread_log() -> Option<std::io::Result<File>> {
    LOG.with(|slot| slot.borrow().as_ref().map(File::try_clone))
}

/// Why a task failed, and the exit code `cargo xtask` ends with.
#[derive(Debug)]
pub struct Failure {
    pub message: String,
    pub code: u8,
}

impl Failure {
    /// A failure with exit code 1.
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            code: 1,
        }
    }
}

pub type Result<T = ()> = std::result::Result<T, Failure>;

/// The repository root (the parent of `xtask/`).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask/ has a parent")
        .to_path_buf()
}

/// The firmware workspace. Cargo reads `firmware/.cargo/config.toml` (target, runner,
/// linker flags) only when run from there, so every firmware command uses it as cwd.
pub fn firmware_dir() -> PathBuf {
    root().join("firmware")
}

/// `cargo`, the same one that runs xtask when possible, without clippy as the
/// workspace's compiler: `.ci/run` builds xtask linted (`crate::tools::host_cargo`), and
/// the builds that must be plain (the firmware images, whose sizes are budgeted; fuzz;
/// installs) would otherwise inherit it.
pub fn cargo() -> Command {
    let mut cargo = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    cargo
        .env_remove("RUSTC_WORKSPACE_WRAPPER")
        .env_remove("CLIPPY_ARGS");
    cargo
}

/// Human-readable form of a command, for the log.
pub fn display(cmd: &Command) -> String {
    let mut line = cmd.get_program().to_string_lossy().into_owned();
    if line.ends_with("/cargo") {
        line = "cargo".into();
    }
    for arg in cmd.get_args() {
        line.push(' ');
        line.push_str(&arg.to_string_lossy());
    }
    match cmd.get_current_dir() {
        Some(dir) if dir != root() => {
            let shown = dir.strip_prefix(root()).unwrap_or(dir);
            format!("(cd {} && {line})", shown.display())
        }
        _ => line,
    }
}

/// Echoes and runs `cmd` (cwd defaults to the repository root), inheriting stdio,
/// and fails unless it exits 0.
pub fn run(cmd: &mut Command) -> Result {
    if cmd.get_current_dir().is_none() {
        cmd.current_dir(root());
    }
    let shown = display(cmd);
    let cannot = |e: std::io::Error| Failure::new(format!("cannot start `{shown}`: {e}"));
    match thread_log() {
        Some(log) => {
            let mut log = log.map_err(cannot)?;
            // A lost echo line is no reason to fail the command.
            let _ = writeln!(log, "$ {shown}");
            cmd.stdout(log.try_clone().map_err(cannot)?).stderr(log);
        }
        None => {
            // The log of every step is stderr's, the command's included: stdout is
            // left to a command's own result (`cargo xtask live`'s JSON lines).
            eprintln!("$ {shown}");
            cmd.stdout(std::io::stderr());
        }
    }
    let status = cmd.status().map_err(cannot)?;
    check(&shown, status)
}

/// As [`run`], but kills `cmd` and fails with code 124 (as coreutils' `timeout`) if it
/// has not finished after `limit`.
pub fn run_with_timeout(cmd: &mut Command, limit: std::time::Duration) -> Result {
    if cmd.get_current_dir().is_none() {
        cmd.current_dir(root());
    }
    let shown = display(cmd);
    println!("$ {shown}   (timeout {} s)", limit.as_secs());
    let mut child = cmd
        .spawn()
        .map_err(|e| Failure::new(format!("cannot start `{shown}`: {e}")))?;
    let deadline = std::time::Instant::now() + limit;
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return check(&shown, status),
            Ok(None) if std::time::Instant::now() < deadline => {
                std::thread::sleep(std::time::Duration::from_millis(50))
            }
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(Failure {
                    message: format!("`{shown}` did not finish within {} s", limit.as_secs()),
                    code: 124,
                });
            }
        }
    }
}

/// Turns a non-zero exit into a [`Failure`] carrying the same code.
pub fn check(shown: &str, status: ExitStatus) -> Result {
    if status.success() {
        return Ok(());
    }
    let code = status
        .code()
        .map_or(1, |c| u8::try_from(c).ok().filter(|&c| c != 0).unwrap_or(1));
    Err(Failure {
        message: format!("`{shown}` failed ({status})"),
        code,
    })
}

/// Runs `cmd` quietly and returns its stdout if it exits 0 (used to probe for tools).
pub fn probe(cmd: &mut Command) -> Option<String> {
    let out = cmd.stdin(std::process::Stdio::null()).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}
