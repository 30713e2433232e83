//! `--positions LIST`: which positions of a motion a run draws (the DXF's position layers,
//! the SVG frames, the printed sheets), for a small file of a few positions. The run still
//! solves every position of the scene (the CSV, the JSON and the diagrams keep them all).
//!
//! A list names values of the motion's drive, in the units a user reads them in on the
//! frames: crank angles φ1 in degrees for a four-bar (`0,90,180`), times t in seconds for a
//! linkage (`0,0.05,0.1`); `every=Δ` takes the first position and every Δ after it
//! (`every=30`: every 30° of crank angle; `every=0.05`: every 0.05 s). A value must be one
//! the run has (the sweep's angles, the time samples: within a millionth of a step), Δ a
//! multiple of the step. The same option (type and parser) serves any command that draws
//! chosen positions.

use std::fmt;
use std::str::FromStr;

/// Which positions to draw, as written after `--positions`.
#[derive(Debug, Clone, PartialEq)]
pub enum Positions {
    /// These drive values (degrees or seconds), in the order given; no two alike.
    List(Vec<f64>),
    /// The first position and every `Δ` of the drive after it (`Δ > 0`).
    Every(f64),
}

/// The drive of a motion as `--positions` reads it: what a value is, in which unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveAxis {
    /// The value's name and symbol as the frames print it (`crank angle φ1`, `time t`).
    pub name: &'static str,
    /// Its unit as written after a number (`°`, ` s`).
    pub unit: &'static str,
    /// The step between positions (the sweep's step, the time step), > 0.
    pub step: f64,
}

/// A value is the position's when within this fraction of a step of it.
pub const MATCH: f64 = 1e-6;

impl FromStr for Positions {
    type Err = String;

    /// `v1,v2,…` (numbers, no two alike) or `every=Δ` (Δ > 0).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        let number = |t: &str| -> Result<f64, String> {
            let v: f64 = t.trim().parse().map_err(|_| format!("`{}` is not a number", t.trim()))?;
            if v.is_finite() { Ok(v) } else { Err(format!("`{}` is not a finite number", t.trim())) }
        };
        let usage = "give a list of positions such as 0,90,180 or a step such as every=30";
        if let Some(step) = s.strip_prefix("every=") {
            let step = number(step).map_err(|e| format!("{e}; {usage}"))?;
            if step <= 0.0 {
                return Err(format!("the step must be greater than 0; {usage}"));
            }
            return Ok(Positions::Every(step));
        }
        if s.is_empty() {
            return Err(format!("the list is empty; {usage}"));
        }
        let mut values = Vec::new();
        for item in s.split(',') {
            if item.trim().is_empty() {
                return Err(format!("`{s}` has an empty item; {usage}"));
            }
            let v = number(item).map_err(|e| format!("{e}; {usage}"))?;
            if values.contains(&v) {
                return Err(format!("{v} is listed twice; {usage}"));
            }
            values.push(v);
        }
        Ok(Positions::List(values))
    }
}

impl fmt::Display for Positions {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Positions::List(v) => {
                let items: Vec<String> = v.iter().map(|x| x.to_string()).collect();
                write!(f, "{}", items.join(","))
            }
            Positions::Every(step) => write!(f, "every={step}"),
        }
    }
}

impl Positions {
    /// The indices into `values` (the drive's value at each position, increasing) of the
    /// positions asked for, in drawing order: a list's in its order, `every=Δ`'s from the
    /// first position on. An error names what is wrong and what the run has.
    pub fn select(&self, values: &[f64], axis: DriveAxis) -> Result<Vec<usize>, String> {
        let (first, last) = match (values.first(), values.last()) {
            (Some(a), Some(b)) => (*a, *b),
            _ => return Err("the run has no position to draw".into()),
        };
        let tol = MATCH * axis.step;
        let fmt = |v: f64| format!("{}{}", crate::draw::plain_decimal(v), axis.unit);
        let range =
            format!("the run's {} goes from {} to {} in steps of {}", axis.name, fmt(first), fmt(last), fmt(axis.step));
        match self {
            Positions::List(wanted) => wanted
                .iter()
                .map(|&v| {
                    let nearest = nearest(values, v);
                    if (values[nearest] - v).abs() <= tol {
                        Ok(nearest)
                    } else {
                        Err(format!(
                            "{} = {} is not a position of the run (the nearest is {}): {range}",
                            axis.name,
                            fmt(v),
                            fmt(values[nearest])
                        ))
                    }
                })
                .collect(),
            Positions::Every(step) => {
                let ratio = step / axis.step;
                if (ratio - ratio.round()).abs() > MATCH * ratio.max(1.0) || ratio.round() < 1.0 {
                    return Err(format!("the step must be a multiple of the run's step, {}: {range}", fmt(axis.step)));
                }
                // Positions at first + m·Δ (the sweep may skip some: those are left out).
                let keep: Vec<usize> = values
                    .iter()
                    .enumerate()
                    .filter(|(_, v)| {
                        let m = ((*v - first) / step).round();
                        (*v - first - m * step).abs() <= tol
                    })
                    .map(|(k, _)| k)
                    .collect();
                Ok(keep)
            }
        }
    }
}

/// Index of the value of `values` nearest `v` (`values` not empty).
fn nearest(values: &[f64], v: f64) -> usize {
    let mut best = 0;
    for (k, x) in values.iter().enumerate() {
        if (x - v).abs() < (values[best] - v).abs() {
            best = k;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEG: DriveAxis = DriveAxis { name: "crank angle φ1", unit: "°", step: 1.0 };

    #[test]
    fn lists_and_steps_parse_and_bad_ones_say_why() {
        assert_eq!("0,90,180".parse(), Ok(Positions::List(vec![0.0, 90.0, 180.0])));
        assert_eq!(" 0.5 , 1e-1 ".parse(), Ok(Positions::List(vec![0.5, 0.1])));
        assert_eq!("every=30".parse(), Ok(Positions::Every(30.0)));
        for (bad, says) in [
            ("", "empty"),
            ("0,,90", "empty item"),
            ("0,x", "`x` is not a number"),
            ("every=0", "greater than 0"),
            ("every=-5", "greater than 0"),
            ("every=", "is not a number"),
            ("1,inf", "finite"),
            ("90,90", "listed twice"),
        ] {
            let e = bad.parse::<Positions>().unwrap_err();
            assert!(e.contains(says), "{bad:?}: {e}");
            assert!(e.contains("0,90,180") && e.contains("every=30"), "{bad:?}: names what is valid: {e}");
        }
        assert_eq!(Positions::List(vec![0.0, 90.5]).to_string(), "0,90.5");
    }

    #[test]
    fn values_pick_the_positions_that_have_them() {
        let values: Vec<f64> = (0..360).map(f64::from).collect();
        assert_eq!(Positions::List(vec![180.0, 0.0, 90.0]).select(&values, DEG), Ok(vec![180, 0, 90]));
        assert_eq!(Positions::Every(90.0).select(&values, DEG), Ok(vec![0, 90, 180, 270]));
        let e = Positions::List(vec![0.0, 45.5]).select(&values, DEG).unwrap_err();
        assert!(e.contains("45.5°") && e.contains("nearest is 45°") && e.contains("from 0° to 359°"), "{e}");
        let e = Positions::List(vec![400.0]).select(&values, DEG).unwrap_err();
        assert!(e.contains("400°"), "{e}");
        let e = Positions::Every(1.5).select(&values, DEG).unwrap_err();
        assert!(e.contains("multiple of the run's step, 1°"), "{e}");
        // Times: 0.1875 s in 360 steps; 0.0501 s is not a sample, 0.05 s (96 steps) is, and
        // every 30 steps.
        let step = 0.1875 / 360.0;
        let times: Vec<f64> = (0..=360).map(|k| f64::from(k) * step).collect();
        let axis = DriveAxis { name: "time t", unit: " s", step };
        assert_eq!(Positions::List(vec![0.015625]).select(&times, axis), Ok(vec![30]));
        assert_eq!(Positions::List(vec![0.05]).select(&times, axis), Ok(vec![96]));
        let e = Positions::List(vec![0.0501]).select(&times, axis).unwrap_err();
        assert!(e.contains("t = 0.0501 s") && e.contains("nearest is 0.05 s"), "{e}");
        assert_eq!(Positions::Every(30.0 * step).select(&times, axis).map(|k| k.len()), Ok(13));
        // A sweep with skipped angles: every=10 takes those it has.
        let gappy: Vec<f64> = [0.0, 10.0, 11.0, 30.0].to_vec();
        assert_eq!(Positions::Every(10.0).select(&gappy, DEG), Ok(vec![0, 1, 3]));
        assert!(Positions::Every(10.0).select(&[], DEG).is_err());
    }
}
