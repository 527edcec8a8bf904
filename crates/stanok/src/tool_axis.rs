//! Tool-axis ticks for `stanok plot` on a 5-axis machine: where tool-centre-point control is on,
//! five ticks per straight move (at 0, ¼, ½, ¾ and the end of the block), each [`TICK_MM`] long
//! from the tip along the tool vector the machine's kinematics give for the pose's rotary values.

#[cfg(test)]
use stanok_canon::Spanned;
use stanok_canon::{Canon, Pose};
use stanok_kin::{FiveAxis, Kinematics};

/// Length of a tick, mm.
pub const TICK_MM: f64 = 10.0;

/// The ticks of a Canon stream, one command at a time: TCP's state is kept between commands.
pub struct Ticks<'a> {
    kinematics: Option<&'a FiveAxis>,
    on: bool,
}

impl<'a> Ticks<'a> {
    /// Ticks for a machine with these kinematics (none without).
    pub fn new(kinematics: Option<&'a FiveAxis>) -> Self {
        Ticks {
            kinematics,
            on: false,
        }
    }

    /// Calls `tick(tip, end)` for each tick of `cmd`.
    pub fn of(&mut self, cmd: &Canon, mut tick: impl FnMut([f64; 3], [f64; 3])) {
        let Some(kin) = self.kinematics else {
            return;
        };
        match cmd {
            Canon::SetToolCentrePoint { active, .. } => self.on = *active,
            Canon::StraightFeed(m) | Canon::StraightTraverse(m) if self.on => {
                let (s, e) = (m.start.to_array(), m.end.to_array());
                for k in 0..=4 {
                    let f = f64::from(k) / 4.0;
                    let p = Pose::from_array(std::array::from_fn(|i| s[i] + (e[i] - s[i]) * f));
                    let t = kin.tool_vector(&p);
                    let tip = p.xyz();
                    tick(tip, std::array::from_fn(|i| tip[i] + TICK_MM * t[i]));
                }
            }
            _ => {}
        }
    }
}

/// The ticks of a whole stream (empty without kinematics or without tool-centre-point control).
#[cfg(test)]
fn ticks(commands: &[Spanned<Canon>], machine: Option<&FiveAxis>) -> Vec<[[f64; 3]; 2]> {
    let mut ticks = Ticks::new(machine);
    let mut out = Vec::new();
    for c in commands {
        ticks.of(&c.value, |a, b| out.push([a, b]));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_canon::{LineMove, Span};

    #[test]
    fn ticks_follow_the_tool_vector_under_tcp_only() {
        let kin = stanok_kin::head_head(stanok_kin::RotaryPair::BC, 0.0).unwrap();
        let tip = Pose {
            z: -100.0,
            ..Pose::ZERO
        };
        let turn = LineMove {
            start: tip,
            end: Pose { b: -75.0, ..tip },
            feed: 600.0,
            law: stanok_canon::FeedLaw::PerMinute,
        };
        let at = |value| Spanned::new(Span::default(), value);
        let stream = [
            at(Canon::StraightFeed(turn.clone())),
            at(Canon::SetToolCentrePoint {
                active: true,
                tool_offset: [0.0, 0.0, 100.0],
            }),
            at(Canon::StraightFeed(turn)),
        ];
        let t = ticks(&stream, Some(&kin));
        // Only the move under TCP: five ticks, the last along B −75: (−sin 75°, 0, cos 75°)·10.
        assert_eq!(t.len(), 5);
        let [a, b] = t[4];
        assert_eq!(a, [0.0, 0.0, -100.0]);
        assert!(
            (b[0] + 9.659258).abs() < 1e-6 && b[1].abs() < 1e-9 && (b[2] + 97.411810).abs() < 1e-6,
            "{b:?}"
        );
        assert!(ticks(&stream, None).is_empty());
    }
}
