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
use crate::solve::fourbar::{Geometry, Kinematics, Position, Prepared, kinematics_eps};

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
    /// A point's velocity (units/s): two channels, x and y.
    Velocity(FourbarPoint),
    /// A point's acceleration (units/s²): two channels, x and y.
    Acceleration(FourbarPoint),
    /// The coupler's angular velocity ω2, rad/s, counter-clockwise positive.
    Omega2,
    /// The rocker's angular velocity ω3, rad/s.
    Omega3,
    /// The coupler's angular acceleration ε2, rad/s².
    Eps2,
    /// The rocker's angular acceleration ε3, rad/s².
    Eps3,
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
            FourbarOutput::Velocity(FourbarPoint::A) => "vA",
            FourbarOutput::Velocity(FourbarPoint::B) => "vB",
            FourbarOutput::Velocity(FourbarPoint::M) => "vM",
            FourbarOutput::Acceleration(FourbarPoint::A) => "aA",
            FourbarOutput::Acceleration(FourbarPoint::B) => "aB",
            FourbarOutput::Acceleration(FourbarPoint::M) => "aM",
            FourbarOutput::Omega2 => "omega2",
            FourbarOutput::Omega3 => "omega3",
            FourbarOutput::Eps2 => "eps2",
            FourbarOutput::Eps3 => "eps3",
        }
    }

    /// The velocity output a scene's `velocities` names (`A`, `B`, `M`: the point's v;
    /// `coupler`, `rocker`: the link's ω).
    pub fn velocity(name: &str) -> Option<FourbarOutput> {
        Some(match FourbarOutput::from_name(name)? {
            FourbarOutput::Point(p) => FourbarOutput::Velocity(p),
            FourbarOutput::Phi2 => FourbarOutput::Omega2,
            FourbarOutput::Phi3 => FourbarOutput::Omega3,
            _ => return None,
        })
    }

    /// The acceleration output a scene's `accelerations` names (a point's a, a link's ε).
    pub fn acceleration(name: &str) -> Option<FourbarOutput> {
        Some(match FourbarOutput::from_name(name)? {
            FourbarOutput::Point(p) => FourbarOutput::Acceleration(p),
            FourbarOutput::Phi2 => FourbarOutput::Eps2,
            FourbarOutput::Phi3 => FourbarOutput::Eps3,
            _ => return None,
        })
    }

    /// Whether it is a rate (a velocity or an acceleration): it needs the kinematics.
    pub fn is_rate(self) -> bool {
        !matches!(self, FourbarOutput::Point(_) | FourbarOutput::Phi2 | FourbarOutput::Phi3)
    }

    /// Whether it is a vector (a point's position, velocity or acceleration).
    pub fn is_vector(self) -> bool {
        matches!(self, FourbarOutput::Point(_) | FourbarOutput::Velocity(_) | FourbarOutput::Acceleration(_))
    }

    /// The point whose position, velocity or acceleration it is.
    pub fn point(self) -> Option<FourbarPoint> {
        match self {
            FourbarOutput::Point(p) | FourbarOutput::Velocity(p) | FourbarOutput::Acceleration(p) => Some(p),
            _ => None,
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

    /// Its channels: 2 for a vector, 1 for an angle or a rate of one.
    pub fn channels(self) -> usize {
        if self.is_vector() { 2 } else { 1 }
    }

    /// Its value(s) at a position (angles in degrees, in (−180, 180]), the rates from
    /// `kin` (zero without).
    fn values(self, pos: &Position, kin: Option<&Kinematics>) -> [f64; 2] {
        let v = |f: &dyn Fn(&Kinematics) -> Vector| kin.map_or([0.0; 2], |k| [f(k).x, f(k).y]);
        let s = |f: &dyn Fn(&Kinematics) -> f64| [kin.map_or(0.0, f), 0.0];
        match self {
            FourbarOutput::Point(p) => {
                let q = point(pos, p);
                [q.x, q.y]
            }
            FourbarOutput::Phi2 => [pos.phi2().to_degrees(), 0.0],
            FourbarOutput::Phi3 => [pos.phi3().to_degrees(), 0.0],
            FourbarOutput::Velocity(p) => v(&|k| rate(k, p).0),
            FourbarOutput::Acceleration(p) => v(&|k| rate(k, p).1),
            FourbarOutput::Omega2 => s(&|k| k.omega2),
            FourbarOutput::Omega3 => s(&|k| k.omega3),
            FourbarOutput::Eps2 => s(&|k| k.eps2),
            FourbarOutput::Eps3 => s(&|k| k.eps3),
        }
    }
}

/// Point `p`'s velocity and acceleration in `k`.
fn rate(k: &Kinematics, p: FourbarPoint) -> (Vector, Vector) {
    match p {
        FourbarPoint::A => (k.v_a, k.a_a),
        FourbarPoint::B => (k.v_b, k.a_b),
        FourbarPoint::M => (k.v_m, k.a_m),
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
    /// The crank's angular velocity (rad/s) and acceleration (rad/s²), the same at every
    /// position (the scene's `omega1`, `epsilon1`).
    crank: (f64, f64),
    /// The nominal's velocities and accelerations at each position when a rate is watched
    /// (`None` at a dead point, or when no rate is watched).
    kinematics: Vec<Option<Kinematics>>,
    /// Channel values of the nominal, position-major.
    nominal: Vec<f64>,
    channels: usize,
}

impl FourbarModel {
    /// The model of `geometry` solved at `positions` (a motion's), with the fields `params`
    /// toleranced and `outputs` watched; the crank turning at 1 rad/s, no angular
    /// acceleration ([`FourbarModel::with_crank`] sets the scene's).
    pub fn new(
        geometry: Geometry,
        positions: &[Position],
        params: Vec<FourbarParam>,
        outputs: Vec<FourbarOutput>,
    ) -> FourbarModel {
        let sides = positions.iter().map(|p| p.side(&geometry).unwrap_or(geometry.branch)).collect();
        let channels = outputs.iter().map(|o| o.channels()).sum();
        let mut model = FourbarModel {
            geometry,
            params,
            outputs,
            positions: positions.to_vec(),
            sides,
            crank: (1.0, 0.0),
            kinematics: Vec::new(),
            nominal: Vec::new(),
            channels,
        };
        model.solve_nominal();
        model
    }

    /// The model with the crank turning at `omega1` (rad/s) with the angular acceleration
    /// `eps1` (rad/s²), both counter-clockwise positive, at every position: what the
    /// velocity and acceleration outputs are taken at.
    pub fn with_crank(mut self, omega1: f64, eps1: f64) -> FourbarModel {
        self.crank = (omega1, eps1);
        self.solve_nominal();
        self
    }

    /// Whether a rate (velocity, acceleration) is watched.
    fn rates(&self) -> bool {
        self.outputs.iter().any(|o| o.is_rate())
    }

    /// The nominal's kinematics (when a rate is watched) and channel values.
    fn solve_nominal(&mut self) {
        let (g, (w, e)) = (self.geometry, self.crank);
        let rates = self.rates();
        self.kinematics =
            self.positions.iter().map(|p| if rates { kinematics_eps(&g, p, w, e).ok() } else { None }).collect();
        self.nominal = Vec::with_capacity(self.positions.len() * self.channels);
        for (p, k) in self.positions.iter().zip(&self.kinematics) {
            for o in &self.outputs {
                self.nominal.extend_from_slice(&o.values(p, k.as_ref())[..o.channels()]);
            }
        }
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
        let dyad = Dyad::at(g, pos)?;
        let kin = if self.rates() { Some(self.kinematics[k].as_ref()?) } else { None };
        let np = self.params.len();
        let mut out = vec![0.0; self.channels * np];
        for (j, p) in self.params.iter().enumerate() {
            let d = dyad.differential(g, pos, *p);
            let r = kin.map(|kin| d.rates(g, pos, kin, self.crank));
            let mut ch = 0;
            for o in &self.outputs {
                let (u, w) = (pos.b - pos.a, pos.b - g.c);
                let vector = |v: Vector, out: &mut [f64]| {
                    out[ch * np + j] = v.x;
                    out[(ch + 1) * np + j] = v.y;
                };
                match (o, &r) {
                    (FourbarOutput::Point(q), _) => vector(d.point(*q), &mut out),
                    (FourbarOutput::Phi2, _) => {
                        out[ch * np + j] = (cross(u, d.db - d.da) / u.norm_squared()).to_degrees();
                    }
                    (FourbarOutput::Phi3, _) => {
                        out[ch * np + j] = (cross(w, d.db - d.dc) / w.norm_squared()).to_degrees();
                    }
                    (FourbarOutput::Velocity(q), Some(r)) => vector(r.velocity(*q), &mut out),
                    (FourbarOutput::Acceleration(q), Some(r)) => vector(r.acceleration(*q), &mut out),
                    (FourbarOutput::Omega2, Some(r)) => out[ch * np + j] = r.omega2,
                    (FourbarOutput::Omega3, Some(r)) => out[ch * np + j] = r.omega3,
                    (FourbarOutput::Eps2, Some(r)) => out[ch * np + j] = r.eps2,
                    (FourbarOutput::Eps3, Some(r)) => out[ch * np + j] = r.eps3,
                    (_, None) => {}
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
        let rates = self.rates();
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
            // The sample's rates at the same crank state; none at its dead point.
            let kin = if rates { kinematics_eps(&g, &p, self.crank.0, self.crank.1).ok() } else { None };
            if rates && kin.is_none() {
                failed[k] = true;
                any = true;
                continue;
            }
            let nominal = &self.nominal[k * ch..(k + 1) * ch];
            let row = &mut out[k * ch..(k + 1) * ch];
            let mut c = 0;
            for o in &self.outputs {
                let v = o.values(&p, kin.as_ref());
                match o {
                    FourbarOutput::Phi2 | FourbarOutput::Phi3 => row[c] = wrap_deg(v[0] - nominal[c]),
                    _ => {
                        for i in 0..o.channels() {
                            row[c + i] = v[i] - nominal[c + i];
                        }
                    }
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

/// The dyad's position equations at a nominal position, for their differentials: u = B − A,
/// w = B − C and their cross product (the determinant of the 2×2 system every
/// differential of B solves: u·dB = r1, w·dB = r2).
struct Dyad {
    u: Vector,
    w: Vector,
    det: f64,
}

/// The differentials of the four-bar's points per unit of one field at a position: the
/// pivots', A's, B's and M's, and the coupler's angle α (radians) and ratio l_bm/l_ab.
struct Differential {
    do1: Vector,
    dc: Vector,
    da: Vector,
    db: Vector,
    dm: Vector,
}

/// The differentials of the rates per unit of one field at a position.
struct RateDifferential {
    dv_a: Vector,
    dv_b: Vector,
    dv_m: Vector,
    da_a: Vector,
    da_b: Vector,
    da_m: Vector,
    omega2: f64,
    omega3: f64,
    eps2: f64,
    eps3: f64,
}

impl RateDifferential {
    fn velocity(&self, p: FourbarPoint) -> Vector {
        match p {
            FourbarPoint::A => self.dv_a,
            FourbarPoint::B => self.dv_b,
            FourbarPoint::M => self.dv_m,
        }
    }

    fn acceleration(&self, p: FourbarPoint) -> Vector {
        match p {
            FourbarPoint::A => self.da_a,
            FourbarPoint::B => self.da_b,
            FourbarPoint::M => self.da_m,
        }
    }
}

impl Dyad {
    /// `None` at a dead point (A, B, C collinear to [`SINGULAR_SIN`](crate::solve::fourbar::SINGULAR_SIN)).
    fn at(g: &Geometry, pos: &Position) -> Option<Dyad> {
        let (u, w) = (pos.b - pos.a, pos.b - g.c);
        let det = cross(u, w);
        (det.abs() > crate::solve::fourbar::SINGULAR_SIN * g.l_ab * g.l_bc).then_some(Dyad { u, w, det })
    }

    /// x with u·x = r1 and w·x = r2.
    #[inline]
    fn solve(&self, r1: f64, r2: f64) -> Vector {
        let (u, w) = (self.u, self.w);
        Vector::new((r1 * w.y - u.y * r2) / self.det, (u.x * r2 - w.x * r1) / self.det)
    }

    /// The points' differentials per unit of field `p`: (B − A)·(dB − dA) = l_ab·dl_ab,
    /// (B − C)·(dB − dC) = l_bc·dl_bc, dA = dO1 + (cos φ1, sin φ1)·dl1, and
    /// M = B + ρ·R(α)·(A − B), ρ = l_bm/l_ab, differentiated.
    fn differential(&self, g: &Geometry, pos: &Position, p: FourbarParam) -> Differential {
        let (mut do1, mut dc) = (Vector::zeros(), Vector::zeros());
        let (mut dl1, mut dlab, mut dlbm, mut dalpha, mut dlbc) = (0.0, 0.0, 0.0, 0.0, 0.0);
        match p {
            FourbarParam::O1x => do1.x = 1.0,
            FourbarParam::O1y => do1.y = 1.0,
            FourbarParam::Cx => dc.x = 1.0,
            FourbarParam::Cy => dc.y = 1.0,
            FourbarParam::L1 => dl1 = 1.0,
            FourbarParam::Lab => dlab = 1.0,
            FourbarParam::Lbm => dlbm = 1.0,
            FourbarParam::AlphaDeg => dalpha = std::f64::consts::PI / 180.0,
            FourbarParam::Lbc => dlbc = 1.0,
        }
        let (s1, c1) = libm::sincos(pos.phi1);
        let da = do1 + Vector::new(c1, s1) * dl1;
        let db = self.solve(self.u.dot(&da) + g.l_ab * dlab, self.w.dot(&dc) + g.l_bc * dlbc);
        let rho = g.l_bm / g.l_ab;
        let (sa, ca) = libm::sincos(g.alpha);
        let rot = |v: Vector| Vector::new(ca * v.x - sa * v.y, sa * v.x + ca * v.y);
        let rv = rot(pos.a - pos.b);
        let drho = dlbm / g.l_ab - g.l_bm * dlab / (g.l_ab * g.l_ab);
        let dm = db + rv * drho + perp(rv) * (rho * dalpha) + rot(da - db) * rho;
        Differential { do1, dc, da, db, dm }
    }
}

impl Differential {
    fn point(&self, p: FourbarPoint) -> Vector {
        match p {
            FourbarPoint::A => self.da,
            FourbarPoint::B => self.db,
            FourbarPoint::M => self.dm,
        }
    }

    /// The rates' differentials at `pos` (nominal kinematics `k`, the crank's ω1 and ε1
    /// fixed): the velocity equations u·(v_B − v_A) = 0, w·v_B = 0 and the acceleration
    /// equations u·(a_B − a_A) + |v_B − v_A|² = 0, w·a_B + |v_B|² = 0 differentiated (the
    /// same 2×2 system as the positions'), v_A = ω1·(A − O1)⊥,
    /// a_A = −ω1²·(A − O1) + ε1·(A − O1)⊥; ω2 = u × (v_B − v_A)/|u|²,
    /// ε2 = u × (a_B − a_A)/|u|² (ω3, ε3 with w, v_B, a_B), and
    /// v_M = v_B + ω2·(M − B)⊥, a_M = a_B − ω2²·(M − B) + ε2·(M − B)⊥.
    fn rates(&self, g: &Geometry, pos: &Position, k: &Kinematics, crank: (f64, f64)) -> RateDifferential {
        let dyad = Dyad { u: pos.b - pos.a, w: pos.b - g.c, det: cross(pos.b - pos.a, pos.b - g.c) };
        let (u, w) = (dyad.u, dyad.w);
        let (du, dw) = (self.db - self.da, self.db - self.dc);
        let (omega1, eps1) = crank;
        let dr1 = self.da - self.do1;
        let dv_a = perp(dr1) * omega1;
        let da_a = -dr1 * (omega1 * omega1) + perp(dr1) * eps1;
        let v_rel = k.v_b - k.v_a;
        let dv_b = dyad.solve(u.dot(&dv_a) - du.dot(&v_rel), -dw.dot(&k.v_b));
        let dv_rel = dv_b - dv_a;
        let a_rel = k.a_b - k.a_a;
        let da_b = dyad
            .solve(u.dot(&da_a) - du.dot(&a_rel) - 2.0 * v_rel.dot(&dv_rel), -dw.dot(&k.a_b) - 2.0 * k.v_b.dot(&dv_b));
        let da_rel = da_b - da_a;
        // d(x × y / |x|²) with x × y / |x|² = value.
        let angular = |x: Vector, dx: Vector, y: Vector, dy: Vector, value: f64| {
            (cross(dx, y) + cross(x, dy)) / x.norm_squared() - 2.0 * value * x.dot(&dx) / x.norm_squared()
        };
        let omega2 = angular(u, du, v_rel, dv_rel, k.omega2);
        let omega3 = angular(w, dw, k.v_b, dv_b, k.omega3);
        let eps2 = angular(u, du, a_rel, da_rel, k.eps2);
        let eps3 = angular(w, dw, k.a_b, da_b, k.eps3);
        let rm = pos.m - pos.b;
        let drm = self.dm - self.db;
        let dv_m = dv_b + perp(rm) * omega2 + perp(drm) * k.omega2;
        let da_m =
            da_b - rm * (2.0 * k.omega2 * omega2) - drm * (k.omega2 * k.omega2) + perp(rm) * eps2 + perp(drm) * k.eps2;
        RateDifferential { dv_a, dv_b, dv_m, da_a, da_b, da_m, omega2, omega3, eps2, eps3 }
    }
}
