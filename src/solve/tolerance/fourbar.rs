//! The four-bar kind under tolerances: its toleranced fields ([`FourbarParam`]), its watched
//! outputs ([`FourbarOutput`]), their exact sensitivities from the closed form, and a sample
//! solved at every position by the closed-form dyad on the nominal's assembly mode
//! ([`FourbarModel`]).
//!
//! Sensitivities: A = O1 + l1·(cos φ1, sin φ1); B solves |B − A| = l_ab, |B − C| = l_bc, so
//! differentiating, (B − A)·(dB − dA) = l_ab·dl_ab and (B − C)·(dB − dC) = l_bc·dl_bc: a 2×2
//! system with the dyad's determinant (B − A) × (B − C) = l_ab·l_bc·sin μ (μ the
//! transmission angle), singular at a dead point. M = B + (l_bm/l_ab)·R(α)·(A − B) is
//! differentiated directly, φ2 and φ3 as the angles of B − A and B − C.

use super::monte_carlo::Model;
use super::wrap_deg;
use crate::geom::{CircleIntersection, Point, Side, Vector, cross, perp};
use crate::solve::fourbar::{Geometry, Position, Prepared, kinematics_eps};

/// A toleranced field of a four-bar scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FourbarParam {
    /// `o1[0]`: x of the crank pivot O1.
    O1x,
    /// `o1[1]`.
    O1y,
    /// `c[0]`: x of the rocker pivot C.
    Cx,
    /// `c[1]`.
    Cy,
    /// `l1`: crank O1A.
    L1,
    /// `l_ab`: coupler side AB.
    Lab,
    /// `l_bm`: coupler side BM.
    Lbm,
    /// `alpha_deg`: the coupler's angle ABM, degrees.
    AlphaDeg,
    /// `l_bc`: rocker BC.
    Lbc,
}

impl FourbarParam {
    /// Every field, in the scene's order.
    pub const ALL: [FourbarParam; 9] = [
        FourbarParam::O1x,
        FourbarParam::O1y,
        FourbarParam::Cx,
        FourbarParam::Cy,
        FourbarParam::L1,
        FourbarParam::Lab,
        FourbarParam::Lbm,
        FourbarParam::AlphaDeg,
        FourbarParam::Lbc,
    ];

    /// The field's path as `--set` names it.
    pub fn field(self) -> &'static str {
        match self {
            FourbarParam::O1x => "o1[0]",
            FourbarParam::O1y => "o1[1]",
            FourbarParam::Cx => "c[0]",
            FourbarParam::Cy => "c[1]",
            FourbarParam::L1 => "l1",
            FourbarParam::Lab => "l_ab",
            FourbarParam::Lbm => "l_bm",
            FourbarParam::AlphaDeg => "alpha_deg",
            FourbarParam::Lbc => "l_bc",
        }
    }

    /// The field named `path`.
    pub fn from_field(path: &str) -> Option<FourbarParam> {
        FourbarParam::ALL.into_iter().find(|p| p.field() == path)
    }

    /// Its nominal value in `g` (degrees for `alpha_deg`).
    pub fn nominal(self, g: &Geometry) -> f64 {
        match self {
            FourbarParam::O1x => g.o1.x,
            FourbarParam::O1y => g.o1.y,
            FourbarParam::Cx => g.c.x,
            FourbarParam::Cy => g.c.y,
            FourbarParam::L1 => g.l1,
            FourbarParam::Lab => g.l_ab,
            FourbarParam::Lbm => g.l_bm,
            FourbarParam::AlphaDeg => g.alpha.to_degrees(),
            FourbarParam::Lbc => g.l_bc,
        }
    }

    /// Adds the deviation `d` (the field's unit) to the field in `g`.
    #[inline]
    pub fn apply(self, g: &mut Geometry, d: f64) {
        match self {
            FourbarParam::O1x => g.o1.x += d,
            FourbarParam::O1y => g.o1.y += d,
            FourbarParam::Cx => g.c.x += d,
            FourbarParam::Cy => g.c.y += d,
            FourbarParam::L1 => g.l1 += d,
            FourbarParam::Lab => g.l_ab += d,
            FourbarParam::Lbm => g.l_bm += d,
            FourbarParam::AlphaDeg => g.alpha += d.to_radians(),
            FourbarParam::Lbc => g.l_bc += d,
        }
    }
}

/// A point of the four-bar that can be watched.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FourbarPoint {
    /// The crank pin A.
    A,
    /// The coupler–rocker joint B.
    B,
    /// The coupler point M.
    M,
}

/// A watched output of the four-bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FourbarOutput {
    /// A point's position: two channels, x and y.
    Point(FourbarPoint),
    /// The coupler's angle φ2 (direction A→B), degrees: one channel.
    Phi2,
    /// The rocker's angle φ3 (direction C→B), degrees: one channel.
    Phi3,
}

impl FourbarOutput {
    /// The output's name in columns: `A`, `B`, `M`, `phi2_deg`, `phi3_deg`.
    pub fn name(self) -> &'static str {
        match self {
            FourbarOutput::Point(FourbarPoint::A) => "A",
            FourbarOutput::Point(FourbarPoint::B) => "B",
            FourbarOutput::Point(FourbarPoint::M) => "M",
            FourbarOutput::Phi2 => "phi2_deg",
            FourbarOutput::Phi3 => "phi3_deg",
        }
    }

    /// The output a scene names (`A`, `B`, `M`, `coupler`, `rocker`, `phi2`, `phi3`).
    pub fn from_name(name: &str) -> Option<FourbarOutput> {
        Some(match name {
            "A" => FourbarOutput::Point(FourbarPoint::A),
            "B" => FourbarOutput::Point(FourbarPoint::B),
            "M" => FourbarOutput::Point(FourbarPoint::M),
            "coupler" | "phi2" | "phi2_deg" => FourbarOutput::Phi2,
            "rocker" | "phi3" | "phi3_deg" => FourbarOutput::Phi3,
            _ => return None,
        })
    }

    /// Its channels: 2 for a point, 1 for an angle.
    pub fn channels(self) -> usize {
        match self {
            FourbarOutput::Point(_) => 2,
            _ => 1,
        }
    }

    /// Its value(s) at a position (angles in degrees, in (−180, 180]).
    fn values(self, pos: &Position) -> [f64; 2] {
        match self {
            FourbarOutput::Point(p) => {
                let q = point(pos, p);
                [q.x, q.y]
            }
            FourbarOutput::Phi2 => [pos.phi2().to_degrees(), 0.0],
            FourbarOutput::Phi3 => [pos.phi3().to_degrees(), 0.0],
        }
    }
}

fn point(pos: &Position, p: FourbarPoint) -> Point {
    match p {
        FourbarPoint::A => pos.a,
        FourbarPoint::B => pos.b,
        FourbarPoint::M => pos.m,
    }
}

/// The four-bar under tolerances: the nominal geometry and its solved positions, the
/// toleranced fields and the watched outputs.
#[derive(Debug, Clone)]
pub struct FourbarModel {
    geometry: Geometry,
    params: Vec<FourbarParam>,
    outputs: Vec<FourbarOutput>,
    /// The nominal's solved positions.
    positions: Vec<Position>,
    /// Each position's assembly mode (side of B from A→C), kept by every sample.
    sides: Vec<Side>,
    /// Channel values of the nominal, position-major.
    nominal: Vec<f64>,
    channels: usize,
}

impl FourbarModel {
    /// The model of `geometry` solved at `positions` (a motion's), with the fields `params`
    /// toleranced and `outputs` watched.
    pub fn new(
        geometry: Geometry,
        positions: &[Position],
        params: Vec<FourbarParam>,
        outputs: Vec<FourbarOutput>,
    ) -> FourbarModel {
        let sides = positions.iter().map(|p| p.side(&geometry).unwrap_or(geometry.branch)).collect();
        let channels = outputs.iter().map(|o| o.channels()).sum();
        let mut nominal = Vec::with_capacity(positions.len() * channels);
        for p in positions {
            for o in &outputs {
                nominal.extend_from_slice(&o.values(p)[..o.channels()]);
            }
        }
        FourbarModel { geometry, params, outputs, positions: positions.to_vec(), sides, nominal, channels }
    }

    /// The nominal channel values, position-major.
    pub fn nominal(&self) -> &[f64] {
        &self.nominal
    }

    /// The watched outputs.
    pub fn outputs(&self) -> &[FourbarOutput] {
        &self.outputs
    }

    /// The nominal positions.
    pub fn nominal_positions(&self) -> &[Position] {
        &self.positions
    }

    /// ∂channel/∂field at position `k`, channel-major (`channels · params` values); `None`
    /// at a dead point (the dyad's determinant zero: A, B, C collinear).
    pub fn sensitivities(&self, k: usize) -> Option<Vec<f64>> {
        let g = &self.geometry;
        let pos = &self.positions[k];
        let (a, b, c) = (pos.a, pos.b, g.c);
        let (u, w) = (b - a, b - c);
        let det = cross(u, w);
        if det.abs() <= crate::solve::fourbar::SINGULAR_SIN * g.l_ab * g.l_bc {
            return None;
        }
        let (s1, c1) = libm::sincos(pos.phi1);
        let rho = g.l_bm / g.l_ab;
        let (sa, ca) = libm::sincos(g.alpha);
        let rot = |v: Vector| Vector::new(ca * v.x - sa * v.y, sa * v.x + ca * v.y);
        let rv = rot(a - b);
        let np = self.params.len();
        let mut out = vec![0.0; self.channels * np];
        for (j, p) in self.params.iter().enumerate() {
            let (mut d_o1, mut d_c) = (Vector::zeros(), Vector::zeros());
            let (mut dl1, mut dlab, mut dlbm, mut dalpha, mut dlbc) = (0.0, 0.0, 0.0, 0.0, 0.0);
            match p {
                FourbarParam::O1x => d_o1.x = 1.0,
                FourbarParam::O1y => d_o1.y = 1.0,
                FourbarParam::Cx => d_c.x = 1.0,
                FourbarParam::Cy => d_c.y = 1.0,
                FourbarParam::L1 => dl1 = 1.0,
                FourbarParam::Lab => dlab = 1.0,
                FourbarParam::Lbm => dlbm = 1.0,
                FourbarParam::AlphaDeg => dalpha = std::f64::consts::PI / 180.0,
                FourbarParam::Lbc => dlbc = 1.0,
            }
            let da = d_o1 + Vector::new(c1, s1) * dl1;
            let r1 = u.dot(&da) + g.l_ab * dlab;
            let r2 = w.dot(&d_c) + g.l_bc * dlbc;
            let db = Vector::new((r1 * w.y - u.y * r2) / det, (u.x * r2 - w.x * r1) / det);
            let drho = dlbm / g.l_ab - g.l_bm * dlab / (g.l_ab * g.l_ab);
            let dm = db + rv * drho + perp(rv) * (rho * dalpha) + rot(da - db) * rho;
            let mut ch = 0;
            for o in &self.outputs {
                match o {
                    FourbarOutput::Point(q) => {
                        let d = match q {
                            FourbarPoint::A => da,
                            FourbarPoint::B => db,
                            FourbarPoint::M => dm,
                        };
                        out[ch * np + j] = d.x;
                        out[(ch + 1) * np + j] = d.y;
                    }
                    FourbarOutput::Phi2 => out[ch * np + j] = (cross(u, db - da) / u.norm_squared()).to_degrees(),
                    FourbarOutput::Phi3 => out[ch * np + j] = (cross(w, db - d_c) / w.norm_squared()).to_degrees(),
                }
                ch += o.channels();
            }
        }
        Some(out)
    }

    /// ∂μ/∂field at position `k` (μ the transmission angle, degrees; `None` at a dead
    /// point) and μ's distance from 0° or 180° there, degrees: how close the tolerances can
    /// bring the dyad to its dead point.
    pub fn transmission(&self, k: usize) -> (Option<Vec<f64>>, f64) {
        let only = FourbarModel {
            outputs: vec![FourbarOutput::Phi2, FourbarOutput::Phi3],
            channels: 2,
            nominal: Vec::new(),
            ..self.clone()
        };
        let mu = self.positions[k].transmission().to_degrees();
        let gap = mu.min(180.0 - mu);
        let s = only.sensitivities(k).map(|s| {
            let np = self.params.len();
            (0..np).map(|j| s[j] - s[np + j]).collect()
        });
        (s, gap)
    }

    /// The unit tangent of point `p`'s nominal path at each position, in the direction of
    /// increasing φ1 (dP/dφ1 normalised; at a dead point, the chord between the neighbours;
    /// a zero vector where neither is defined).
    pub fn tangents(&self, p: FourbarPoint) -> Vec<Vector> {
        let g = &self.geometry;
        let n = self.positions.len();
        let raw: Vec<Option<Vector>> = self
            .positions
            .iter()
            .map(|pos| match p {
                FourbarPoint::A => Some(perp(pos.a - g.o1)),
                _ => kinematics_eps(g, pos, 1.0, 0.0).ok().map(|k| if p == FourbarPoint::B { k.v_b } else { k.v_m }),
            })
            .collect();
        (0..n)
            .map(|k| {
                let t = raw[k].filter(|v| v.norm() > 0.0).unwrap_or_else(|| {
                    let (i, j) = (k.saturating_sub(1), (k + 1).min(n - 1));
                    point(&self.positions[j], p) - point(&self.positions[i], p)
                });
                let len = t.norm();
                if len > 0.0 && len.is_finite() { t / len } else { Vector::zeros() }
            })
            .collect()
    }
}

impl Model for FourbarModel {
    type Work = ();

    fn positions(&self) -> usize {
        self.positions.len()
    }

    fn channels(&self) -> usize {
        self.channels
    }

    fn work(&self) {}

    fn evaluate(&self, _: &mut (), dev: &[f64], out: &mut [f64], failed: &mut [bool]) -> bool {
        let mut g = self.geometry;
        for (p, d) in self.params.iter().zip(dev) {
            p.apply(&mut g, *d);
        }
        if !(g.l1 > 0.0 && g.l_ab > 0.0 && g.l_bm >= 0.0 && g.l_bc > 0.0) {
            failed.iter_mut().for_each(|f| *f = true);
            return true;
        }
        let prep = Prepared::new(&g);
        let ch = self.channels;
        let mut any = false;
        for (k, (pos, side)) in self.positions.iter().zip(&self.sides).enumerate() {
            let b = match prep.dyad(pos.phi1) {
                Ok((a, CircleIntersection::Two { left, right })) => {
                    Some((a, if *side == Side::Left { left } else { right }))
                }
                Ok((a, CircleIntersection::Tangent(b))) => Some((a, b)),
                _ => None,
            };
            let Some((a, b)) = b else {
                failed[k] = true;
                any = true;
                continue;
            };
            let p = prep.complete(pos.phi1, a, b);
            let nominal = &self.nominal[k * ch..(k + 1) * ch];
            let row = &mut out[k * ch..(k + 1) * ch];
            let mut c = 0;
            for o in &self.outputs {
                match o {
                    FourbarOutput::Point(q) => {
                        let v = point(&p, *q);
                        row[c] = v.x - nominal[c];
                        row[c + 1] = v.y - nominal[c + 1];
                    }
                    _ => row[c] = wrap_deg(o.values(&p)[0] - nominal[c]),
                }
                c += o.channels();
            }
        }
        any
    }
}

impl super::Sensitive for FourbarModel {
    fn sensitivities(&self, k: usize) -> Option<Vec<f64>> {
        FourbarModel::sensitivities(self, k)
    }

    fn dead_point(&self, k: usize, dims: &[super::Dimension]) -> Option<String> {
        let (s, gap) = self.transmission(k);
        let s = s?;
        let reach: f64 = s.iter().zip(dims).map(|(s, d)| s.abs() * d.half() + (s * d.mid()).abs()).sum();
        (reach > super::DEAD_POINT_FRACTION * gap).then(|| {
            format!(
                "near a dead point: the transmission angle is {gap:.3}° from 0° or 180° and the tolerances move it by up to {reach:.3}°"
            )
        })
    }
}
