//! Text for people: the `cuesight collide` summary ([`CollideAnswer`]'s `Display`) and
//! a one-line [`Summary`] of any answer (what `cargo xtask run` prints).

use core::fmt;

use crate::answer::{Answer, CollideAnswer, InputEcho};

/// `(x, y, z)` with fixed-width components, for aligned columns.
struct Vector([f32; 3]);

impl fmt::Display for Vector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [x, y, z] = self.0;
        write!(f, "({x:9.4}, {y:9.4}, {z:9.4})")
    }
}

/// `(x, y, z)` with three decimals.
struct Short([f32; 3]);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [x, y, z] = self.0;
        write!(f, "({x:.3}, {y:.3}, {z:.3})")
    }
}

/// `mu 0.05`, or `mu 0.00995 + 0.108 exp(-1.088 v)` for a speed-dependent law.
struct Friction<'a>(&'a InputEcho);

impl fmt::Display for Friction<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = self.0;
        if i.mu_b == 0.0 && i.mu_c == 0.0 {
            write!(f, "mu {}", i.mu)
        } else {
            write!(f, "mu {} + {} exp(-{} v)", i.mu, i.mu_b, i.mu_c)
        }
    }
}

/// Human-readable summary, a few lines, no trailing newline (`cuesight collide`).
impl fmt::Display for CollideAnswer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = &self.input;
        let spin_kind = if i.roll { " (natural roll)" } else { "" };
        writeln!(
            f,
            "model {}, regime {}",
            self.model.name(),
            self.regime.name()
        )?;
        writeln!(
            f,
            "input:  speed {} m/s, cut {} deg, w {} rad/s{spin_kind}",
            i.speed,
            i.cut_deg,
            Vector(i.spin)
        )?;
        writeln!(
            f,
            "        {}, e* {}, mu_s {}, R {} m, M {} kg",
            Friction(i),
            i.restitution,
            i.mu_s,
            i.radius,
            i.mass
        )?;
        for (name, ball) in [("cue:   ", &self.cue), ("object:", &self.object)] {
            writeln!(
                f,
                "{name} v {} m/s   w {} rad/s",
                Vector(ball.v),
                Vector(ball.w)
            )?;
        }
        write!(
            f,
            "throw {:.3} deg, cue deflection {:.3} deg, separation {:.3} deg",
            self.throw_deg, self.cue_deflection_deg, self.separation_deg
        )
    }
}

/// One line about an answer, for a log or a terminal.
pub struct Summary<'a>(pub &'a Answer);

impl fmt::Display for Summary<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Answer::Collide(c) => write!(
                f,
                "{} {}: object v {} m/s, throw {:.2} deg; cue v {} m/s, w {} rad/s, deflection {:.2} deg",
                c.model.name(),
                c.regime.name(),
                Short(c.object.v),
                c.throw_deg,
                Short(c.cue.v),
                Short(c.cue.w),
                c.cue_deflection_deg
            ),
            Answer::Params(p) => {
                write!(f, "defaults now: model {}, ", p.model.name())?;
                if p.mu_b == 0.0 && p.mu_c == 0.0 {
                    write!(f, "mu {}", p.mu)?;
                } else {
                    write!(f, "mu {} + {} exp(-{} v)", p.mu, p.mu_b, p.mu_c)?;
                }
                write!(
                    f,
                    ", e* {}, mu_s {}, R {} m, M {} kg",
                    p.restitution, p.mu_s, p.radius, p.mass
                )
            }
            Answer::Stroke(s) => write!(
                f,
                "cue {:.3} m/s at the tip -> ball {:.3} m/s, w {} rad/s ({} samples, impact at #{}, {:.3} s of stroke)",
                s.cue_speed,
                s.ball_speed,
                Short(s.ball_spin),
                s.samples,
                s.impact_index,
                s.stroke_duration
            ),
            Answer::StrokeChunk(c) => write!(
                f,
                "stroke samples held: {} of {}",
                c.samples, c.capacity
            ),
            Answer::Version(v) => write!(
                f,
                "protocol {}, {} on {}; lines up to {} bytes, strokes up to {} samples in chunks of {}",
                v.protocol, v.firmware, v.board, v.max_line, v.stroke_capacity, v.max_samples
            ),
            Answer::Shutdown(s) => write!(
                f,
                "session over: {} requests answered, {} with an error",
                s.requests, s.errors
            ),
            Answer::Error(e) => {
                write!(f, "error {}", e.kind.name())?;
                if let Some(field) = &e.field {
                    write!(f, " [{field}]")?;
                }
                write!(f, ": {}", e.message)
            }
        }
    }
}
