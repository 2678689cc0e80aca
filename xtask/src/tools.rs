//! Installs what the checks need, only when it is missing (idempotent and silent when
//! everything is present): the Cortex-M target and clippy/rustfmt through rustup,
//! QEMU and a C++ compiler through apt, defmt-print, flip-link and cargo-fuzz through
//! `cargo install`.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::Command;

use crate::cmd::{self, probe, Failure, Result};

/// The firmware's target (Cortex-M4F with FPU).
pub const TARGET: &str = "thumbv7em-none-eabihf";

/// Everything the host and firmware checks need before QEMU: the target, clippy, rustfmt.
pub fn ensure_toolchain() -> Result {
    if probe(Command::new("rustup").arg("--version")).is_none() {
        eprintln!("xtask: rustup not found; assuming the toolchain already has {TARGET}, clippy and rustfmt");
        return ensure_flip_link();
    }
    let targets =
        probe(Command::new("rustup").args(["target", "list", "--installed"])).unwrap_or_default();
    if !targets.lines().any(|t| t.trim() == TARGET) {
        eprintln!("xtask: installing the Rust target {TARGET}");
        cmd::run(Command::new("rustup").args(["target", "add", TARGET]))?;
    }
    let components = probe(Command::new("rustup").args(["component", "list", "--installed"]))
        .unwrap_or_default();
    let missing: Vec<&str> = ["clippy", "rustfmt"]
        .into_iter()
        .filter(|c| {
            !components
                .lines()
                .any(|l| l.trim() == *c || l.starts_with(&format!("{c}-")))
        })
        .collect();
    if !missing.is_empty() {
        eprintln!(
            "xtask: installing the rustup components {}",
            missing.join(", ")
        );
        cmd::run(
            Command::new("rustup")
                .args(["component", "add"])
                .args(&missing),
        )?;
    }
    ensure_flip_link()
}

/// `flip-link`, the firmware's linker (`firmware/.cargo/config.toml`): it puts the stack
/// below the static data, so an overflow runs off the start of RAM and faults instead
/// of overwriting `.bss`/`.data`. Installed with `cargo install --locked` if missing;
/// when it is only in cargo's bin directory, that directory is put on this process's
/// `PATH` so the cargo commands below find it.
pub fn ensure_flip_link() -> Result {
    // flip-link passes its arguments on to the real linker (`--version` included), so
    // it is looked for as a file rather than run.
    let on_path = || {
        std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())
            .any(|dir| dir.join("flip-link").is_file())
    };
    if on_path() {
        return Ok(());
    }
    let in_cargo_bin = || {
        cargo_bin_dir()
            .map(|dir| dir.join("flip-link"))
            .filter(|path| path.is_file())
    };
    if in_cargo_bin().is_none() {
        eprintln!("xtask: flip-link not found; installing it with cargo install");
        cmd::run(cmd::cargo().args(["install", "flip-link", "--locked"]))?;
    }
    let Some(found) = in_cargo_bin() else {
        return Err(Failure::new(
            "flip-link was installed but is neither on PATH nor in cargo's bin directory",
        ));
    };
    let dir = found.parent().map(PathBuf::from).unwrap_or_default();
    let mut paths = vec![dir];
    paths.extend(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    ));
    let joined = std::env::join_paths(paths)
        .map_err(|e| Failure::new(format!("putting flip-link on PATH: {e}")))?;
    std::env::set_var("PATH", joined);
    Ok(())
}

fn cargo_bin_dir() -> Option<PathBuf> {
    std::env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cargo")))
        .map(|h| h.join("bin"))
}

/// Everything `cargo xtask run` needs: the target, QEMU and defmt-print.
pub fn ensure_for_qemu() -> Result {
    ensure_toolchain()?;
    ensure_qemu()?;
    defmt_print().map(drop)
}

/// `build` (a `cargo build`, or a build cargo runs for another tool: maturin's) made to
/// lint the workspace's own crates as `cargo clippy -- -D warnings` would: clippy-driver
/// as their compiler (`RUSTC_WORKSPACE_WRAPPER` and `CLIPPY_ARGS`, what `cargo clippy`
/// sets for its `cargo check`). The build fails on a lint and still compiles everything;
/// the dependencies are compiled once, for the build, where a separate `cargo clippy`
/// compiled them once more in check mode (the Python package: 60 s of clippy beside its
/// pip build in a bare-machine CI run). Only workspace members are linted, as `cargo
/// clippy` lints them: the path dependencies outside the workspace (core, link, sensors)
/// have their own clippy run in the host workspace.
///
/// clippy-driver compiles the crates it lints with MIR optimisations off, so what it
/// builds is not byte for byte what a plain build makes: the firmware images, whose
/// sizes are held to budgets, are never built this way (the live image came out 56 B
/// smaller). The Python extension CI builds is for its tests alone (it is already built
/// without LTO, in 16 codegen units); MIR optimisation changes no f32 result, and the
/// tests hold every number to the CLI's bits.
pub fn lint_while_building(build: &mut Command) -> Result<&mut Command> {
    let driver = clippy_driver()?;
    Ok(build.env("RUSTC_WORKSPACE_WRAPPER", driver).env(
        "CLIPPY_ARGS",
        "-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__",
    ))
}

/// `cargo` for a build of the host workspace in the dev/test profile (its tests, the
/// CLI), linted as it builds ([`lint_while_building`]). Every such build of `cargo xtask
/// test` goes through here: the wrapper is part of cargo's fingerprint, so one build
/// without it would compile the workspace's crates again (and one with it after a plain
/// `cargo test` does once). Replaces a separate `cargo clippy --workspace
/// --all-targets`, which compiled every dependency once more in check mode: on a fresh
/// clone (2026-11-27, two cores, `CARGO_INCREMENTAL=0`) the test build took 199 s, the
/// linted one with the examples and benches 219 s, where the clippy step took 80 s.
pub fn host_cargo() -> Result<Command> {
    let mut cargo = cmd::cargo();
    lint_while_building(&mut cargo)?;
    Ok(cargo)
}

/// The toolchain's clippy-driver (the clippy component, see [`ensure_toolchain`]).
fn clippy_driver() -> Result<PathBuf> {
    probe(Command::new("rustup").args(["which", "clippy-driver"]))
        .map(|path| PathBuf::from(path.trim()))
        .or_else(|| {
            probe(Command::new("clippy-driver").arg("--version")).map(|_| "clippy-driver".into())
        })
        .ok_or_else(|| {
            Failure::new("clippy-driver not found: `rustup component add clippy` installs it")
        })
}

/// `qemu-system-arm`, from Debian/Ubuntu's `qemu-system-arm` package if missing.
pub fn ensure_qemu() -> Result {
    if probe(Command::new("qemu-system-arm").arg("--version")).is_some() {
        return Ok(());
    }
    eprintln!("xtask: qemu-system-arm not found; installing the Debian package qemu-system-arm");
    let apt = Apt::for_missing("qemu-system-arm")?;
    apt.run(&["update"])?;
    // `--no-remove`: never trade a package the machine already has for QEMU.
    let plain = apt.run(&[
        "install",
        "-y",
        "--no-install-recommends",
        "--no-remove",
        "qemu-system-arm",
    ]);
    if let Err(failure) = plain {
        // Typically a qemu-utils from backports that the stable qemu-system-arm would
        // replace: take qemu-system-arm from the same backports suite instead.
        eprintln!(
            "xtask: {}; trying the distribution's backports suite",
            failure.message
        );
        install_qemu_from_backports(&apt)?;
    }
    if probe(Command::new("qemu-system-arm").arg("--version")).is_none() {
        return Err(Failure::new(
            "qemu-system-arm still not runnable after installing it",
        ));
    }
    Ok(())
}

/// Path of `defmt-print` (1.x, the version that decodes defmt 1 frames), installed
/// with `cargo install --locked --debug` if missing: unoptimised, it still decodes a
/// log far faster than QEMU writes one, and it builds in a fraction of the optimised
/// build's time (118 s on a bare two-core CI machine, every step waiting for it).
pub fn defmt_print() -> Result<PathBuf> {
    if let Some(found) = find_defmt_print() {
        return Ok(found);
    }
    eprintln!("xtask: defmt-print not found; installing it with cargo install (about a minute)");
    cmd::run(lowest_priority(cmd::cargo()).args([
        "install",
        "defmt-print",
        "--locked",
        "--version",
        "^1",
        "--debug",
    ]))?;
    find_defmt_print().ok_or_else(|| {
        Failure::new(
            "defmt-print was installed but is neither on PATH nor in cargo's bin directory",
        )
    })
}

/// `command` under `nice -n 19` where coreutils' `nice` runs, else `command` itself:
/// `cargo xtask test` builds defmt-print beside its first steps, and at the lowest
/// priority that build takes only the CPU they leave idle (a test binary running on
/// one core, a link, a download).
fn lowest_priority(command: Command) -> Command {
    if probe(Command::new("nice").arg("true")).is_none() {
        return command;
    }
    let mut niced = Command::new("nice");
    niced
        .args(["-n", "19"])
        .arg(command.get_program())
        .args(command.get_args());
    niced
}

fn find_defmt_print() -> Option<PathBuf> {
    let on_path = PathBuf::from("defmt-print");
    let cargo_home = std::env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cargo")));
    let in_cargo_bin = cargo_home.map(|h| h.join("bin").join("defmt-print"));
    [Some(on_path), in_cargo_bin]
        .into_iter()
        .flatten()
        .find(|p| probe(Command::new(p).arg("--version")).is_some())
}

/// The cargo-fuzz version installed when `cargo fuzz` is missing.
pub const CARGO_FUZZ_VERSION: &str = "0.13.2";

/// `cargo fuzz` (cargo-fuzz, which builds and runs the libFuzzer targets of `fuzz/`),
/// installed with `cargo install --locked` at [`CARGO_FUZZ_VERSION`] if missing.
pub fn ensure_cargo_fuzz() -> Result {
    let runs = || probe(cmd::cargo().args(["fuzz", "--version"])).is_some();
    if runs() {
        return Ok(());
    }
    eprintln!("xtask: cargo-fuzz not found; installing it with cargo install (about a minute)");
    cmd::run(cmd::cargo().args([
        "install",
        "cargo-fuzz",
        "--locked",
        "--version",
        CARGO_FUZZ_VERSION,
    ]))?;
    if runs() {
        Ok(())
    } else {
        Err(Failure::new(
            "cargo-fuzz was installed but `cargo fuzz --version` does not run",
        ))
    }
}

/// A C++ compiler, which libfuzzer-sys needs to build libFuzzer from source: `$CXX`,
/// `c++` or `g++`, else Debian's `g++` through apt (the machine may have only gcc).
pub fn ensure_cxx() -> Result {
    let found = || {
        std::env::var_os("CXX")
            .into_iter()
            .chain(["c++".into(), "g++".into()])
            .any(|cxx| probe(Command::new(cxx).arg("--version")).is_some())
    };
    if found() {
        return Ok(());
    }
    eprintln!("xtask: no C++ compiler (c++, g++) found; installing the Debian package g++ (libfuzzer-sys compiles libFuzzer)");
    let apt = Apt::for_missing("a C++ compiler (g++)")?;
    apt.run(&["update"])?;
    apt.run(&[
        "install",
        "-y",
        "--no-install-recommends",
        "--no-remove",
        "g++",
    ])?;
    if found() {
        Ok(())
    } else {
        Err(Failure::new(
            "g++ was installed but neither c++ nor g++ runs",
        ))
    }
}

/// `apt-get`, through sudo when needed, with extra `-o` options.
struct Apt {
    sudo: Vec<&'static str>,
    extra: Vec<String>,
}

impl Apt {
    /// apt-get as root, or through sudo (non-interactive without a terminal), to install
    /// `what`; fails, naming `what`, when there is no apt-get or no way to become root.
    fn for_missing(what: &str) -> Result<Self> {
        if probe(Command::new("apt-get").arg("--version")).is_none() {
            return Err(Failure::new(format!(
                "{what} is missing and apt-get is not available: install it by hand"
            )));
        }
        let sudo: Vec<&'static str> = if is_root() {
            vec![]
        } else if probe(Command::new("sudo").arg("--version")).is_some() {
            // Without a terminal nobody can type a password: fail instead of hanging.
            if std::io::stdin().is_terminal() {
                vec!["sudo"]
            } else {
                vec!["sudo", "-n"]
            }
        } else {
            return Err(Failure::new(format!(
                "{what} is missing and installing it needs root (no sudo found)"
            )));
        };
        Ok(Self {
            sudo,
            extra: Vec::new(),
        })
    }

    fn run(&self, args: &[&str]) -> Result {
        let mut all: Vec<String> = self.sudo.iter().map(|s| s.to_string()).collect();
        all.extend(["apt-get".to_string(), "-q".to_string()]);
        // Wait for another apt or dpkg (an unattended upgrade, a second xtask) instead of
        // failing at once on its lock: a CI run lost its QEMU install that way.
        all.extend(["-o".to_string(), "DPkg::Lock::Timeout=600".to_string()]);
        all.extend(self.extra.iter().cloned());
        all.extend(args.iter().map(|s| s.to_string()));
        cmd::run(
            Command::new(&all[0])
                .args(&all[1..])
                .env("DEBIAN_FRONTEND", "noninteractive"),
        )
    }
}

/// Debian only: installs qemu-system-arm from `<codename>-backports`, added for this
/// one command through a private copy of the source list (the system's apt
/// configuration and package lists are left as they were).
fn install_qemu_from_backports(apt: &Apt) -> Result {
    let os_release = std::fs::read_to_string("/etc/os-release").unwrap_or_default();
    let field = |key: &str| {
        os_release
            .lines()
            .find_map(|l| l.strip_prefix(key).and_then(|v| v.strip_prefix('=')))
            .map(|v| v.trim_matches('"').to_string())
    };
    let (Some("debian"), Some(codename)) = (field("ID").as_deref(), field("VERSION_CODENAME"))
    else {
        return Err(Failure::new(
            "qemu-system-arm cannot be installed without removing packages; install it by hand",
        ));
    };
    let dir = std::env::temp_dir().join("xtask-apt-backports");
    let parts = dir.join("sources.list.d");
    let lists = dir.join("lists");
    let io = |e: std::io::Error| Failure::new(format!("preparing {}: {e}", dir.display()));
    std::fs::create_dir_all(&parts).map_err(io)?;
    std::fs::create_dir_all(lists.join("partial")).map_err(io)?;
    if let Ok(entries) = std::fs::read_dir("/etc/apt/sources.list.d") {
        for entry in entries.flatten() {
            let name = entry.file_name();
            let name = name.to_string_lossy();
            if name.ends_with(".list") || name.ends_with(".sources") {
                std::fs::copy(entry.path(), parts.join(&*name)).map_err(io)?;
            }
        }
    }
    let backports = format!(
        "Types: deb\nURIs: http://deb.debian.org/debian\nSuites: {codename}-backports\nComponents: main\n\
         Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg\n"
    );
    std::fs::write(parts.join("xtask-backports.sources"), backports).map_err(io)?;
    let apt = Apt {
        sudo: apt.sudo.clone(),
        extra: vec![
            "-o".into(),
            format!("Dir::Etc::sourceparts={}", parts.display()),
            "-o".into(),
            format!("Dir::State::lists={}", lists.display()),
        ],
    };
    apt.run(&["update"])?;
    let release = format!("{codename}-backports");
    apt.run(&[
        "install",
        "-y",
        "--no-install-recommends",
        "--no-remove",
        "-t",
        &release,
        "qemu-system-arm",
    ])
}

fn is_root() -> bool {
    probe(Command::new("id").arg("-u")).is_some_and(|uid| uid.trim() == "0")
}
