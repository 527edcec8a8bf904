//! The built-in functions of the AxiOMA high-level language: the math library (angles in
//! degrees), FTABLE/STABLE, strlen, sprintf, settable_zs/settable_wcs. Each checks its arity
//! and its domain and gives a diagnostic instead of a non-finite value.

use super::eval::{Env, Undo};
use super::format::sprintf;
use super::value::{binary, finite, HVal, MAX_STRING};
use stanok_canon::setup::{WorkpieceFrame, ZeroOffset};
use stanok_canon::Diagnostic;
use stanok_syntax::hll::{HBinOp, HExprId};
use stanok_syntax::ColSpan;

type R<T> = Result<T, Diagnostic>;

impl Env<'_> {
    /// A built-in function. Names are matched without regard to case (`FTABLE`, `ftable`).
    pub(super) fn call(&mut self, name: ColSpan, args: &[HExprId], at: ColSpan) -> R<HVal> {
        let fname = self.name(name).to_ascii_lowercase();
        let shown = self.name(name).to_string();
        let block = self.block;
        let arity = |n: std::ops::RangeInclusive<usize>| -> R<()> {
            if n.contains(&args.len()) {
                Ok(())
            } else {
                Err(Diagnostic::error(
                    "hll::arguments",
                    format!(
                        "`{}` takes {} argument{}, not {}",
                        shown,
                        if n.start() == n.end() {
                            n.start().to_string()
                        } else {
                            format!("{} … {}", n.start(), n.end())
                        },
                        if *n.end() == 1 { "" } else { "s" },
                        args.len()
                    ),
                    block.span_of(at),
                ))
            }
        };
        let domain = |env: &Self, ok: bool, what: &str| -> R<()> {
            if ok {
                Ok(())
            } else {
                Err(env.err("hll::domain", format!("`{fname}`: {what}"), at))
            }
        };
        let one = |env: &mut Self| -> R<f64> {
            arity(1..=1)?;
            Ok(env.numbers(args, at, &fname)?[0])
        };
        let v = match fname.as_str() {
            "sin" => one(self)?.to_radians().sin(),
            "cos" => one(self)?.to_radians().cos(),
            "tan" => {
                let x = one(self)?;
                domain(
                    self,
                    (x / 90.0 - 1.0).rem_euclid(2.0) != 0.0,
                    "tan(90° + k·180°) is infinite",
                )?;
                x.to_radians().tan()
            }
            "asin" | "acos" => {
                let x = one(self)?;
                domain(
                    self,
                    (-1.0..=1.0).contains(&x),
                    "the argument must be in −1 … 1",
                )?;
                if fname == "asin" {
                    x.asin().to_degrees()
                } else {
                    x.acos().to_degrees()
                }
            }
            "atan" => one(self)?.atan().to_degrees(),
            "atan2" => {
                arity(2..=2)?;
                let v = self.numbers(args, at, &fname)?;
                v[0].atan2(v[1]).to_degrees()
            }
            "sqrt" => {
                let x = one(self)?;
                domain(self, x >= 0.0, "negative argument")?;
                x.sqrt()
            }
            "exp" => one(self)?.exp(),
            "log" | "log10" => {
                let x = one(self)?;
                domain(self, x > 0.0, "the argument must be positive")?;
                if fname == "log" {
                    x.ln()
                } else {
                    x.log10()
                }
            }
            "pow" => {
                arity(2..=2)?;
                let v = self.numbers(args, at, &fname)?;
                v[0].powf(v[1])
            }
            "floor" => one(self)?.floor(),
            "ceil" => one(self)?.ceil(),
            // C's round: halves away from zero.
            "round" => one(self)?.round(),
            "trunc" => one(self)?.trunc(),
            "fabs" => one(self)?.abs(),
            "abs" => {
                arity(1..=1)?;
                let v = self.eval(args[0])?;
                return match v {
                    HVal::Int(i) => i
                        .checked_abs()
                        .map(HVal::Int)
                        .ok_or_else(|| self.err("hll::arithmetic", "integer overflow", at)),
                    HVal::Bool(b) => Ok(HVal::Int(b as i64)),
                    HVal::Double(d) => Ok(HVal::Double(d.abs())),
                    HVal::Str(_) => Err(self.err("hll::type-mismatch", "`abs` of a string", at)),
                };
            }
            "min" | "max" => {
                arity(2..=2)?;
                let a = self.eval(args[0])?;
                let b = self.eval(args[1])?;
                let less =
                    binary(HBinOp::Lt, a.clone(), b.clone()).map_err(|m| self.arith_err(m, at))?;
                let a_first = (less == HVal::Bool(true)) == (fname == "min");
                let (pick, other) = if a_first { (a, b) } else { (b, a) };
                // Mixed int/double: the result is double, as C's usual conversions.
                return Ok(match (pick, other) {
                    (HVal::Int(i), HVal::Double(_)) => HVal::Double(i as f64),
                    (p, _) => p,
                });
            }
            "ftable" | "stable" => {
                arity(1..=1)?;
                let i = self.eval(args[0])?;
                let table = if fname == "ftable" {
                    &self.machine.feed_table
                } else {
                    &self.machine.speed_table
                };
                return match i {
                    HVal::Int(i) if (0..128).contains(&i) && (i as usize) < table.len() => {
                        Ok(HVal::Double(table[i as usize]))
                    }
                    other => Err(self.err(
                        "axioma::table-index",
                        format!(
                            "{}({}): the table index is an integer 0 … 127",
                            fname.to_ascii_uppercase(),
                            match other {
                                HVal::Str(s) => format!("\"{s}\""),
                                v => v.number().unwrap_or(0.0).to_string(),
                            }
                        ),
                        at,
                    )),
                };
            }
            "strlen" => {
                arity(1..=1)?;
                return match self.eval(args[0])? {
                    HVal::Str(s) => Ok(HVal::Int(s.chars().count() as i64)),
                    v => Err(self.err(
                        "hll::type-mismatch",
                        format!("`strlen` of a {}", v.kind()),
                        at,
                    )),
                };
            }
            "sprintf" => return self.sprintf(args, at),
            "settable_zs" => return self.settable(args, at, true),
            "settable_wcs" => return self.settable(args, at, false),
            _ => {
                return Err(self.err(
                    "hll::unknown-function",
                    format!("unknown function `{}`", self.name(name)),
                    name,
                ))
            }
        };
        finite(v).map_err(|m| self.err("hll::domain", m, at))
    }

    /// `sprintf(str, format, args…)`: formats into the string variable `str`; returns the length.
    fn sprintf(&mut self, args: &[HExprId], at: ColSpan) -> R<HVal> {
        if args.len() < 2 {
            return Err(self.err(
                "hll::arguments",
                "`sprintf` takes a string variable, a format and its arguments",
                at,
            ));
        }
        let place = self.place(args[0])?;
        let fmt = match self.eval(args[1])? {
            HVal::Str(s) => s,
            v => {
                return Err(self.err(
                    "hll::type-mismatch",
                    format!("the format must be a string, not a {}", v.kind()),
                    self.span(args[1]),
                ))
            }
        };
        let mut values = Vec::with_capacity(args.len() - 2);
        for &a in &args[2..] {
            values.push(self.eval(a)?);
        }
        let text = sprintf(&fmt, &values).map_err(|m| self.err("hll::format", m, at))?;
        if text.chars().count() > MAX_STRING {
            return Err(self.err(
                "hll::string-length",
                format!("the result is longer than {MAX_STRING} characters"),
                at,
            ));
        }
        let len = text.chars().count() as i64;
        if !matches!(self.read(&place), HVal::Str(_)) {
            return Err(self.err(
                "hll::type-mismatch",
                "sprintf writes into a string variable",
                self.span(args[0]),
            ));
        }
        self.write(&place, HVal::Str(text), at)?;
        Ok(HVal::Int(len))
    }

    /// `settable_zs(g, page, x, y, z [, a, b, c])`: zero offset G54…G59 (`g` = 54…59) page 1…32;
    /// `settable_wcs(g, page, x, y, z, phi, theta, psi)`: workpiece system G154…G159 (`g` =
    /// 154…159), origin in machine mm and Euler angles ZY'Z'' in degrees. Values in mm/deg, not
    /// affected by G70/G71 (spec §9 [D]). The new values are read the next time the table entry
    /// is selected (G54…/G154… in a later block), like Sinumerik's settable frames.
    fn settable(&mut self, args: &[HExprId], at: ColSpan, zero: bool) -> R<HVal> {
        let (name, first, range) = if zero {
            ("settable_zs", 54.0, 5..=8)
        } else {
            ("settable_wcs", 154.0, 8..=8)
        };
        if !range.contains(&args.len()) {
            return Err(self.err(
                "hll::arguments",
                if zero {
                    "`settable_zs(g, page, x, y, z [, a, b, c])` takes 5 … 8 arguments"
                } else {
                    "`settable_wcs(g, page, x, y, z, phi, theta, psi)` takes 8 arguments"
                },
                at,
            ));
        }
        let v = self.numbers(args, at, name)?;
        let system = v[0] - first;
        if system.fract() != 0.0 || !(0.0..=5.0).contains(&system) {
            return Err(self.err(
                "hll::domain",
                format!(
                    "`{name}`: the table is G{} … G{}, not {}",
                    first,
                    first + 5.0,
                    v[0]
                ),
                self.span(args[0]),
            ));
        }
        if v[1].fract() != 0.0 || !(1.0..=32.0).contains(&v[1]) {
            return Err(self.err(
                "axioma::page-range",
                format!(
                    "`{name}`: page {} out of range: the tables have pages 1 to 32",
                    v[1]
                ),
                self.span(args[1]),
            ));
        }
        let (s, p) = (system as usize, v[1] as usize - 1);
        if zero {
            let old = self.control.offsets.zero[s][p];
            // X Y Z, then A B C when given (spec §9 [D]: one value per programmable coordinate).
            let mut axes = [0.0; 9];
            axes[..v.len() - 2].copy_from_slice(&v[2..]);
            let new = ZeroOffset {
                offset: stanok_canon::Pose::from_array(axes),
                rotation_xy: 0.0,
            };
            self.control.offsets.zero[s][p] = new;
            self.vars.journal.push(Undo::Zero(s, p, old));
        } else {
            let old = self.control.offsets.workpiece[s][p];
            self.control.offsets.workpiece[s][p] = WorkpieceFrame {
                origin: [v[2], v[3], v[4]],
                euler: [v[5], v[6], v[7]],
            };
            self.vars.journal.push(Undo::Wcs(s, p, old));
        }
        Ok(HVal::Int(0))
    }
}
