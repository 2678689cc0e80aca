//! Issue 4's CI check, from the disassembly: the f32 `KimGrip` hot path calls no
//! software double-precision routine and uses the FPU's `vsqrt.f32`.
//!
//! `bench-firmware`'s `kimgrip-probe` image calls `cuesight::collide(.., KimGrip)` from
//! one unmangled function, `cuesight_kimgrip_f32` (release build, fat LTO: `collide`
//! is inlined there with the model known, so other models' code is not part of it).
//! `llvm-objdump` disassembles the image; every function reachable from the root
//! through direct branches (calls and tail calls, resolved by target address) is the
//! hot path. It fails on a reachable soft-f64 routine (`__aeabi_d*`, `__adddf3`, …),
//! a libm f64 function or libm's software `sqrtf`, any `.f64` instruction, an indirect
//! branch it cannot follow, or no `vsqrt.f32` at all. It checks both math backends,
//! then boots each probe in QEMU (every shot must give a finite outcome).

use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;
use std::process::Command;
use std::time::{Duration, Instant};

use super::firmware::{bench_firmware_dir, target_dir};
use crate::cmd::{self, probe, Failure, Result};
use crate::tools;

const PROBE: &str = "kimgrip-probe";
const ROOT: &str = "cuesight_kimgrip_f32";

/// Builds, disassembles and checks the probe for each backend, then runs it.
pub fn check_kimgrip() -> Result {
    let objdump = llvm_objdump()?;
    tools::ensure_qemu()?;
    for backend in ["libm", "micromath"] {
        cmd::run(
            cmd::cargo()
                .args(["build", "--release", "--bin", PROBE])
                .args(["--no-default-features", "--features", backend])
                .current_dir(bench_firmware_dir()),
        )?;
        let elf = target_dir().join(tools::TARGET).join("release").join(PROBE);
        let listing = probe(
            Command::new(&objdump)
                .args(["--disassemble", "--demangle", "--no-show-raw-insn"])
                .arg(&elf),
        )
        .ok_or_else(|| {
            Failure::new(format!("{} failed on {}", objdump.display(), elf.display()))
        })?;
        let report = analyse(&listing, ROOT)
            .map_err(|why| Failure::new(format!("KimGrip f32 hot path ({backend}): {why}")))?;
        println!("xtask: KimGrip f32 hot path ({backend}): {report}");
        run_probe(&elf)?;
    }
    Ok(())
}

/// Boots the probe in QEMU; it exits 0 when every shot gave a finite outcome.
fn run_probe(elf: &std::path::Path) -> Result {
    let mut qemu = Command::new("qemu-system-arm");
    qemu.args(["-machine", "mps2-an386", "-cpu", "cortex-m4", "-nographic"])
        .args(["-semihosting-config", "enable=on,target=native", "-kernel"])
        .arg(elf)
        .stdin(std::process::Stdio::null());
    let shown = cmd::display(&qemu);
    println!("$ {shown}");
    let mut child = qemu
        .spawn()
        .map_err(|e| Failure::new(format!("cannot start qemu-system-arm: {e}")))?;
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return cmd::check(&shown, status),
            Ok(None) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(20)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(Failure::new(format!("{shown}: no exit within 30 s")));
            }
        }
    }
}

/// `llvm-objdump` of the toolchain's `llvm-tools` component, added with rustup if
/// missing; otherwise one on PATH.
pub(super) fn llvm_objdump() -> Result<PathBuf> {
    if let Some(found) = find_objdump() {
        return Ok(found);
    }
    println!("xtask: llvm-objdump not found; adding the rustup component llvm-tools");
    let added =
        cmd::run(Command::new("rustup").args(["component", "add", "llvm-tools"])).or_else(|_| {
            cmd::run(Command::new("rustup").args(["component", "add", "llvm-tools-preview"]))
        });
    if let Err(failure) = added {
        println!("xtask: {}", failure.message);
    }
    find_objdump().ok_or_else(|| {
        Failure::new(
            "llvm-objdump is missing: `rustup component add llvm-tools` (or put one on PATH)",
        )
    })
}

fn find_objdump() -> Option<PathBuf> {
    let sysroot = probe(Command::new("rustc").args(["--print", "sysroot"]))?;
    let host = probe(Command::new("rustc").arg("-vV"))?
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))?;
    let bundled = PathBuf::from(sysroot.trim())
        .join("lib/rustlib")
        .join(host)
        .join("bin/llvm-objdump");
    [bundled, PathBuf::from("llvm-objdump")]
        .into_iter()
        .find(|p| probe(Command::new(p).arg("--version")).is_some())
}

/// One disassembled function.
pub(super) struct Function {
    pub(super) name: String,
    /// `(address, mnemonic, operands)`.
    pub(super) instructions: Vec<(u64, String, String)>,
}

/// Parses `llvm-objdump -d --no-show-raw-insn` output into functions by start address.
pub(super) fn parse(listing: &str) -> BTreeMap<u64, Function> {
    let mut functions = BTreeMap::new();
    let mut current: Option<u64> = None;
    for line in listing.lines() {
        // `00000870 <name>:` starts a function.
        if let Some((address, rest)) = line.split_once(' ') {
            if let (Ok(address), Some(name)) = (
                u64::from_str_radix(address, 16),
                rest.strip_prefix('<').and_then(|r| r.strip_suffix(">:")),
            ) {
                functions.insert(
                    address,
                    Function {
                        name: name.to_string(),
                        instructions: Vec::new(),
                    },
                );
                current = Some(address);
                continue;
            }
        }
        // `     926:      \tvsqrt.f32\ts0, s0`
        let Some((address, rest)) = line.trim_start().split_once(':') else {
            continue;
        };
        let (Ok(address), Some(f)) = (
            u64::from_str_radix(address, 16),
            current.and_then(|c| functions.get_mut(&c)),
        ) else {
            continue;
        };
        let mut parts = rest.trim().splitn(2, '\t');
        let mnemonic = parts.next().unwrap_or_default().trim().to_string();
        let operands = parts.next().unwrap_or_default().trim().to_string();
        if !mnemonic.is_empty() && !mnemonic.starts_with('.') {
            f.instructions.push((address, mnemonic, operands));
        }
    }
    functions
}

/// `b`, `bl`, `b.w`, `bne`, `beq.w`, `cbz`, `blx` … (not `bic`, `bfi`, `bkpt`, `bx`).
pub(super) fn is_branch(mnemonic: &str) -> bool {
    let m = mnemonic.strip_suffix(".w").unwrap_or(mnemonic);
    const CONDITIONS: [&str; 15] = [
        "", "eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt",
    ];
    const MORE: [&str; 3] = ["gt", "le", "al"];
    m == "bl"
        || m == "blx"
        || m == "cbz"
        || m == "cbnz"
        || m.strip_prefix('b')
            .is_some_and(|c| CONDITIONS.contains(&c) || MORE.contains(&c))
}

/// A branch whose target is in a register (or loaded into `pc`).
fn is_indirect(mnemonic: &str, operands: &str) -> bool {
    let m = mnemonic.strip_suffix(".w").unwrap_or(mnemonic);
    match m {
        "blx" | "bx" => !operands.starts_with("0x") && operands != "lr",
        // `ldr pc, [sp], #4` is a one-register pop: a return.
        "mov" | "ldr" => operands.starts_with("pc,") && !operands.starts_with("pc, [sp]"),
        _ => false,
    }
}

/// The first `0x…` operand: a direct branch's absolute target.
pub(super) fn target(operands: &str) -> Option<u64> {
    let hex = operands
        .split_whitespace()
        .find_map(|t| t.strip_prefix("0x"))?;
    u64::from_str_radix(hex.trim_end_matches(','), 16).ok()
}

/// A software double-precision routine, a libm f64 function, or libm's software sqrtf.
fn forbidden(name: &str) -> Option<&'static str> {
    let segments: Vec<&str> = name.split("::").collect();
    let last = segments
        .iter()
        .rev()
        .find(|s| !(s.starts_with('h') && s.len() == 17))
        .copied()
        .unwrap_or(name);
    if let Some(op) = last.strip_prefix("__aeabi_") {
        if op.starts_with('d') || op.ends_with("2d") {
            return Some("software f64 (AEABI)");
        }
    }
    if last.starts_with("__") && last.contains("df") {
        return Some("software f64 (compiler-builtins)");
    }
    if let Some(at) = segments.iter().position(|s| *s == "libm") {
        if segments.get(at + 1) == Some(&"math") {
            let function = segments.get(at + 2).copied().unwrap_or_default();
            if function == "sqrtf" {
                return Some("software sqrtf instead of vsqrt.f32");
            }
            if name.contains("f64")
                || (segments.get(at + 3) == Some(&function) && !function.ends_with('f'))
            {
                return Some("libm f64 function");
            }
        }
    }
    None
}

/// Walks the call graph from the function named `root` and applies the rules; a
/// one-line summary.
fn analyse(listing: &str, root: &str) -> std::result::Result<String, String> {
    let functions = parse(listing);
    let name = root;
    let root = functions
        .iter()
        .find(|(_, f)| f.name == name || f.name.starts_with(&format!("{name}::h")))
        .map(|(a, _)| *a)
        .ok_or_else(|| format!("no function `{name}` in the image"))?;
    let owner = |address: u64| functions.range(..=address).next_back().map(|(a, _)| *a);

    let mut reached = BTreeSet::from([root]);
    // Shortest call chain to each function, to explain a failure.
    let mut via: BTreeMap<u64, u64> = BTreeMap::new();
    let mut queue = vec![root];
    let mut problems = Vec::new();
    while let Some(at) = queue.pop() {
        let f = &functions[&at];
        for (address, mnemonic, operands) in &f.instructions {
            if is_indirect(mnemonic, operands) {
                problems.push(format!(
                    "indirect branch `{mnemonic} {operands}` at {address:#x} in {}",
                    f.name
                ));
            }
            if mnemonic.ends_with(".f64") {
                problems.push(format!(
                    "double-precision instruction `{mnemonic}` at {address:#x} in {}",
                    f.name
                ));
            }
            if !is_branch(mnemonic) {
                continue;
            }
            if let Some(callee) = target(operands).and_then(owner) {
                if callee != at && reached.insert(callee) {
                    via.insert(callee, at);
                    queue.push(callee);
                }
            }
        }
    }
    let chain = |mut at: u64| {
        let mut names = vec![functions[&at].name.clone()];
        while let Some(&caller) = via.get(&at) {
            names.push(functions[&caller].name.clone());
            at = caller;
        }
        names.reverse();
        names.join(" -> ")
    };
    for &at in &reached {
        if let Some(why) = forbidden(&functions[&at].name) {
            problems.push(format!("{why}: {}", chain(at)));
        }
    }
    let sqrts: usize = reached
        .iter()
        .map(|a| {
            functions[a]
                .instructions
                .iter()
                .filter(|(_, m, _)| m == "vsqrt.f32")
                .count()
        })
        .sum();
    if sqrts == 0 {
        problems.push("no vsqrt.f32 instruction in the reachable code".into());
    }
    if !problems.is_empty() {
        return Err(problems.join("; "));
    }
    let count: usize = reached
        .iter()
        .map(|a| functions[a].instructions.len())
        .sum();
    Ok(format!(
        "{} functions, {count} instructions reachable from {name}; {sqrts} vsqrt.f32, \
         no software f64, no libm f64 or sqrtf, no indirect branch",
        reached.len()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    const LISTING: &str = "\
00000870 <cuesight_kimgrip_f32>:
     870:      \tpush\t{r4, r5, r7, lr}
     874:      \tvsqrt.f32\ts0, s0
     878:      \tbl\t0x900 <helper> @ imm = #0x84
     87c:      \tbne\t0x874 <cuesight_kimgrip_f32+0x4> @ imm = #-0xc
     880:      \tpop\t{r4, r5, r7, pc}

00000900 <helper>:
     900:      \tbx\tlr

00000a00 <__aeabi_dmul>:
     a00:      \tbx\tlr
";

    #[test]
    fn clean_path_passes() {
        let report = analyse(LISTING, ROOT).unwrap();
        assert!(
            report.starts_with("2 functions, 6 instructions"),
            "{report}"
        );
    }

    #[test]
    fn soft_f64_call_fails_with_its_chain() {
        let bad = LISTING.replace(
            "\tbx\tlr\n\n00000a00",
            "\tb.w\t0xa00 <__aeabi_dmul>\n\n00000a00",
        );
        let why = analyse(&bad, ROOT).unwrap_err();
        assert!(
            why.contains("cuesight_kimgrip_f32 -> helper -> __aeabi_dmul"),
            "{why}"
        );
    }

    #[test]
    fn missing_vsqrt_fails() {
        let bad = LISTING.replace("vsqrt.f32\ts0, s0", "vmul.f32\ts0, s0, s0");
        assert!(analyse(&bad, ROOT).unwrap_err().contains("no vsqrt.f32"));
    }

    #[test]
    fn classification() {
        assert!(forbidden("compiler_builtins::float::add::__adddf3").is_some());
        assert!(forbidden("__aeabi_f2d").is_some());
        assert!(forbidden("__aeabi_memcpy4").is_none());
        assert!(forbidden("libm::math::sqrt::sqrt::ha04281f338628b8f").is_some());
        assert!(forbidden("libm::math::sqrtf::sqrtf::ha04281f338628b8f").is_some());
        assert!(forbidden("libm::math::expf::expf::h2635e3780cb158a0").is_none());
        assert!(is_branch("beq.w") && is_branch("bl") && !is_branch("bic") && !is_branch("bx"));
        assert!(is_indirect("blx", "r3") && !is_indirect("bx", "lr"));
    }
}
