//! `cuesight` command line: predict what happens when a spinning cue ball hits a
//! resting object ball. The clap interface lives here; the logic in
//! [`cuesight_cli::cli`].

use std::io::Write;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use cuesight_cli::calibrate::ParamsFile;
use cuesight_cli::cli;
use cuesight_cli::report;
use cuesight_link::{Collide, ModelName};

/// Predict what happens when a spinning cue ball hits a resting object ball.
#[derive(Parser)]
#[command(name = "cuesight", version, arg_required_else_help = false)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Predict both balls' velocities and spins just after the impact.
    ///
    /// Collision frame: x from the cue-ball centre to the object-ball centre, z up,
    /// y = z × x. SI units: m, s, kg, rad/s; angles in degrees. Exit codes: 0 ok,
    /// 1 invalid physical value, 2 usage error.
    Collide(CollideArgs),
    /// Shot guidance: where to aim to pocket a ball, and where both balls go.
    ///
    /// Scene from a TOML or JSON file (--scene) and/or flags (flags override the file).
    /// Table frame: x along the length, y across, origin at a corner of the playing
    /// surface; metres, m/s, degrees counter-clockwise from +x. With --solve, or with a
    /// pocket and no aim, solves the aim (throw included) and reports its correction
    /// against the ghost-ball aim; with --aim, plays it. Exit codes: 0 ok, 1 invalid
    /// value or no aim found, 2 usage error. See docs/shot-cli.md.
    Shot(cuesight_cli::shot_cli::Flags),
    /// Talk to a cuesight device: requests as JSON lines in, one answer per request out.
    ///
    /// Reads requests (the link's JSON, e.g. {"collide":{"speed":2,"cut":30}}; see
    /// docs/protocol.md) from --session FILE or stdin, one per line, sends each as a
    /// frame and prints each answer as a one-line summary, or as JSON with --json. At
    /// connect it checks the device's schema. Session files: `#` headings, `##`
    /// comments, `!expect-error ` before a request whose answer must be an error. Exit
    /// codes: 0 ok, 1 unexpected error answers (listed at the end), 2 usage, 3 link
    /// failure, 4 schema mismatch.
    Device(cuesight_cli::device::Flags),
    /// Fit the ball–ball friction law (and e*) to measured throw.
    ///
    /// Reads measured throw (JSON or CSV, see docs/calibration.md), fits
    /// μ(v) = mu + mu_b·exp(−mu_c·v) (--fit mu-v, the default), a constant μ (mu) or
    /// μ(v) and e* (mu-v-e) by weighted least squares, and prints the parameters with
    /// uncertainties, per-point residuals and the RMS; --json prints one object that
    /// `collide --params` and `shot --params` read. Exit codes: 0 ok, 1 bad data or no
    /// convergence, 2 usage error.
    Calibrate(cuesight_cli::calibrate::Flags),
}

#[derive(Args)]
struct CollideArgs {
    /// Cue-ball speed before impact U (m/s).
    #[arg(long, value_name = "U", allow_negative_numbers = true)]
    speed: f32,
    /// Cut angle φ in degrees, |φ| < 90 (velocity U (cos φ, sin φ, 0)).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    cut: f32,
    /// Cue-ball angular velocity in rad/s (topspin is WY > 0) [default: 0,0,0, stun];
    /// or --roll, or --tip.
    #[arg(long, value_name = "WX,WY,WZ", allow_hyphen_values = true,
          value_parser = cli::parse_spin, conflicts_with = "roll")]
    spin: Option<[f32; 3]>,
    /// Natural roll for the given velocity instead of --spin.
    #[arg(long)]
    roll: bool,
    /// Spin from a cue strike instead of --spin: the tip offset in ball radii, as `shot
    /// --tip` (side > 0 right english, height > 0 follow, |b| <= 0.5; 0,0.4 is natural
    /// roll). The ball arrives with the spin the strike gives at speed U (the cloth's
    /// effect on the way is not applied); the spin is echoed in rad/s.
    #[arg(long, value_name = "SIDE,HEIGHT", allow_hyphen_values = true,
          value_parser = cli::parse_tip, conflicts_with_all = ["spin", "roll"])]
    tip: Option<[f32; 2]>,
    /// Contact parameters from a JSON file (mu, mu_b, mu_c, restitution, mu_s, radius,
    /// mass; what `cuesight calibrate --json` prints); flags given override it.
    #[arg(long, value_name = "FILE")]
    params: Option<std::path::PathBuf>,
    /// Ball–ball friction coefficient μ (with --mu-b/--mu-c: the high-speed limit a)
    /// [default: 0.05].
    #[arg(long, allow_negative_numbers = true)]
    mu: Option<f32>,
    /// Speed-dependent friction μ(v) = mu + B·exp(−C·v), v the slip speed (TP A.14):
    /// the amplitude B [default: 0, constant μ].
    #[arg(long, value_name = "B", allow_negative_numbers = true)]
    mu_b: Option<f32>,
    /// The decay rate C (s/m) of the speed-dependent friction [default: 0].
    #[arg(long, value_name = "C", allow_negative_numbers = true)]
    mu_c: Option<f32>,
    /// Energetic coefficient of restitution e* [default: 0.95].
    #[arg(long, allow_negative_numbers = true)]
    restitution: Option<f32>,
    /// Object-ball/table static friction coefficient μ_s [default: 0.3].
    #[arg(long, allow_negative_numbers = true)]
    mu_s: Option<f32>,
    /// Ball radius R (m) [default: 0.028575].
    #[arg(long, allow_negative_numbers = true)]
    radius: Option<f32>,
    /// Ball mass M (kg) [default: 0.17].
    #[arg(long, allow_negative_numbers = true)]
    mass: Option<f32>,
    /// Model: one of the core's (ideal, kim, kim-grip, ...) or reference, the f64
    /// first-principles solver.
    #[arg(long, default_value = "kim-grip", value_parser = cli::parse_model)]
    model: ModelName,
    /// With --model auto: the accepted error of the tier auto picks, relative to U, in
    /// (0, 1] (auto evaluates the cheapest tier whose a-priori estimate is within it)
    /// [default: 1e-3].
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    tolerance: Option<f32>,
    /// Print one JSON object on one line instead of the summary.
    #[arg(long)]
    json: bool,
}

fn main() -> ExitCode {
    let parsed = match Cli::try_parse() {
        Ok(parsed) => parsed,
        // --help and --version print to stdout and exit 0 (a failed write as any
        // other output's).
        Err(error) if !error.use_stderr() => {
            return match error.print().and_then(|()| std::io::stdout().flush()) {
                Ok(()) => ExitCode::from(u8::try_from(error.exit_code()).unwrap_or(0)),
                Err(e) => ExitCode::from(cli::output_error(&e)),
            };
        }
        Err(error) => {
            cli::error_line(cli::usage_error_message(&error));
            return ExitCode::from(cli::EXIT_USAGE);
        }
    };
    let args = match parsed.command {
        Command::Collide(args) => args,
        Command::Shot(flags) => return cuesight_cli::shot_cli::main(&flags),
        Command::Device(flags) => return cuesight_cli::device::main(&flags),
        Command::Calibrate(flags) => return cuesight_cli::calibrate::main(&flags),
    };
    // Flags override the --params file; what neither gives is the pool default.
    let file = match &args.params {
        Some(path) => match ParamsFile::read(path) {
            Ok(file) => file,
            Err(message) => {
                cli::error_line(message);
                return ExitCode::from(cli::EXIT_USAGE);
            }
        },
        None => ParamsFile::default(),
    };
    let mut request = Collide {
        speed: args.speed,
        cut: args.cut,
        spin: args.spin,
        roll: args.roll,
        mu: args.mu.or(file.mu),
        mu_b: args.mu_b.or(file.mu_b),
        mu_c: args.mu_c.or(file.mu_c),
        restitution: args.restitution.or(file.restitution),
        mu_s: args.mu_s.or(file.mu_s),
        radius: args.radius.or(file.radius),
        mass: args.mass.or(file.mass),
        model: Some(args.model),
    };
    if let Some(tip) = args.tip {
        match cli::tip_spin(&request, tip) {
            Ok(spin) => request.spin = Some(spin),
            Err(error) => {
                cli::error_line(&error);
                return ExitCode::from(error.exit_code());
            }
        }
    }
    match cli::collide_within(&request, args.tolerance) {
        Ok((report, pick)) if args.json => {
            cli::print_line(report::to_json_with(&report, pick.as_ref()))
        }
        Ok((report, pick)) => cli::write_output(|out| {
            writeln!(out, "{}", report::Text(&report))?;
            match &pick {
                Some(pick) => writeln!(out, "{}", report::AutoLine(pick)),
                None => Ok(()),
            }
        }),
        Err(error) => {
            cli::error_line(&error);
            ExitCode::from(error.exit_code())
        }
    }
}
