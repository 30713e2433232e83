//! The 6R triad under tolerances: its toleranced fields ([`TriadParam`]: a pivot's
//! coordinate, a radius, a side of the triangle), its watched outputs ([`TriadOutput`]: a
//! vertex's position, a link's angle φ_i, the triangle's angle), their exact sensitivities
//! from the closure equations, and a sample solved in each of the nominal's assembly modes
//! ([`TriadModel`]). A triad does not move: its "positions" are its assembly modes.
//!
//! Sensitivities (implicit function theorem on the three-angle system of
//! [`newton`](mod@crate::solve::triad::newton)): with A_i = O_i + R_i·e_i, e_i = (cos φ_i, sin φ_i),
//!
//! g_ij(φ, p) = (|A_i − A_j|² − l_ij²) / (2·l_ij) = 0,   ij = 12, 23, 13,
//!
//! so J·dφ = −∂g/∂p·dp with J = ∂g/∂φ (J_ij,i = (A_i − A_j)·R_i·e_i⊥ / l_ij, the solver's own
//! Jacobian) and, at a solution (|A_i − A_j| = l_ij), ∂g_ij/∂A_i = (A_i − A_j)/l_ij = −∂g_ij/∂A_j,
//! ∂g_ij/∂l_ij = −1, while a pivot moves its vertex by dO_i and a radius by e_i·dR_i. A vertex
//! then moves by dA_i = dO_i + e_i·dR_i + R_i·e_i⊥·dφ_i. Singular where J is: the links
//! O1A1, O2A2, O3A3 concurrent (or parallel), the triad's dead point.
//!
//! Samples: each sample's triad is solved in every assembly mode of the nominal by
//! Newton–Raphson on the three-angle system from the nominal mode's angles (the seed's
//! analytic reference; quadratic from a start this close). A mode the sample cannot keep —
//! the triangle does not close, Newton does not converge, the configuration reached has the
//! other orientation or lies nearer another nominal mode than its own (the modes have merged
//! and parted) — is counted as not assembled there.

use super::monte_carlo::Model;
use super::{Dimension, wrap_deg};
use crate::geom::{Point, Vector, cross, perp};
use crate::solve::triad::newton::{NEWTON_RESIDUAL_REL, NewtonOptions, newton_to, solve3, system};
use crate::solve::triad::{Configuration, Orientation, Triad};

/// Newton iterations a sample is allowed in one mode (it converges in 3–5 from the
/// nominal's angles under tolerances).
pub const SAMPLE_ITERATIONS: usize = 30;

/// The step of the central difference of the relative determinant of J that measures how
/// fast the tolerances bring a mode to its dead point, relative to [`Triad::scale`].
pub const DETERMINANT_STEP: f64 = 1e-6;

/// A toleranced field of a triad scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TriadParam {
    /// Coordinate `coord` (0 x, 1 y) of ground pivot O_{pivot+1}: `o1[0]` … `o3[1]`.
    Pivot {
        /// 0, 1, 2 for O1, O2, O3.
        pivot: usize,
        /// 0 x, 1 y.
        coord: usize,
    },
    /// Radius R_{i+1} = O_iA_i: `r[0]`, `r[1]`, `r[2]`.
    Radius(usize),
    /// The triangle's side A1A2: `l12`.
    L12,
    /// Side A2A3: `l23`.
    L23,
    /// Side A1A3: `l13`.
    L13,
}

impl TriadParam {
    /// Every field, in the scene's order.
    pub const ALL: [TriadParam; 12] = [
        TriadParam::Pivot { pivot: 0, coord: 0 },
        TriadParam::Pivot { pivot: 0, coord: 1 },
        TriadParam::Pivot { pivot: 1, coord: 0 },
        TriadParam::Pivot { pivot: 1, coord: 1 },
        TriadParam::Pivot { pivot: 2, coord: 0 },
        TriadParam::Pivot { pivot: 2, coord: 1 },
        TriadParam::Radius(0),
        TriadParam::Radius(1),
        TriadParam::Radius(2),
        TriadParam::L12,
        TriadParam::L23,
        TriadParam::L13,
    ];

    /// The field's path as `--set` names it.
    pub fn field(self) -> String {
        match self {
            TriadParam::Pivot { pivot, coord } => format!("o{}[{coord}]", pivot + 1),
            TriadParam::Radius(i) => format!("r[{i}]"),
            TriadParam::L12 => "l12".into(),
            TriadParam::L23 => "l23".into(),
            TriadParam::L13 => "l13".into(),
        }
    }

    /// The field named `path`.
    pub fn from_field(path: &str) -> Option<TriadParam> {
        TriadParam::ALL.into_iter().find(|p| p.field() == path)
    }

    /// Its nominal value in `t`.
    pub fn nominal(self, t: &Triad) -> f64 {
        match self {
            TriadParam::Pivot { pivot, coord } => {
                if coord == 0 {
                    t.o[pivot].x
                } else {
                    t.o[pivot].y
                }
            }
            TriadParam::Radius(i) => t.r[i],
            TriadParam::L12 => t.l12,
            TriadParam::L23 => t.l23,
            TriadParam::L13 => t.l13,
        }
    }

    /// Adds the deviation `d` to the field in `t` (unchecked: a sample's lengths are
    /// checked before it is solved).
    #[inline]
    pub fn apply(self, t: &mut Triad, d: f64) {
        match self {
            TriadParam::Pivot { pivot, coord: 0 } => t.o[pivot].x += d,
            TriadParam::Pivot { pivot, .. } => t.o[pivot].y += d,
            TriadParam::Radius(i) => t.r[i] += d,
            TriadParam::L12 => t.l12 += d,
            TriadParam::L23 => t.l23 += d,
            TriadParam::L13 => t.l13 += d,
        }
    }

    /// Its direct part of the closure: how far it moves each vertex per unit (with the
    /// vertices' directions `e`), and each side (rows 12, 23, 13) per unit.
    fn direct(self, e: &[Vector; 3]) -> ([Vector; 3], [f64; 3]) {
        let mut da = [Vector::zeros(); 3];
        let mut dl = [0.0; 3];
        match self {
            TriadParam::Pivot { pivot, coord } => {
                if coord == 0 {
                    da[pivot].x = 1.0
                } else {
                    da[pivot].y = 1.0
                }
            }
            TriadParam::Radius(i) => da[i] = e[i],
            TriadParam::L12 => dl[0] = 1.0,
            TriadParam::L23 => dl[1] = 1.0,
            TriadParam::L13 => dl[2] = 1.0,
        }
        (da, dl)
    }
}

/// A watched output of the triad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TriadOutput {
    /// Vertex A_{i+1}'s position: two channels, x and y.
    Vertex(usize),
    /// φ_{i+1}, the direction O_i → A_i, degrees: one channel.
    Phi(usize),
    /// The triangle's angle (direction A1 → A2), degrees: one channel.
    Triangle,
}

impl TriadOutput {
    /// The output's name in columns: `A1`…`A3`, `phi1_deg`…`phi3_deg`, `triangle_deg`.
    pub fn name(self) -> String {
        match self {
            TriadOutput::Vertex(i) => format!("A{}", i + 1),
            TriadOutput::Phi(i) => format!("phi{}_deg", i + 1),
            TriadOutput::Triangle => "triangle_deg".into(),
        }
    }

    /// The point a scene names (`A1`, `A2`, `A3`).
    pub fn point(name: &str) -> Option<TriadOutput> {
        (0..3).map(TriadOutput::Vertex).find(|o| o.name() == name)
    }

    /// The angle a scene names (`phi1`…`phi3`, `link1`…`link3` for φ1…φ3, `triangle`).
    pub fn angle(name: &str) -> Option<TriadOutput> {
        match name {
            "triangle" | "triangle_deg" => Some(TriadOutput::Triangle),
            _ => (0..3)
                .find(|i| {
                    [format!("phi{}", i + 1), format!("phi{}_deg", i + 1), format!("link{}", i + 1)]
                        .iter()
                        .any(|n| n == name)
                })
                .map(TriadOutput::Phi),
        }
    }

    /// Its channels: 2 for a vertex, 1 for an angle.
    pub fn channels(self) -> usize {
        match self {
            TriadOutput::Vertex(_) => 2,
            _ => 1,
        }
    }

    /// Its value(s) in configuration `c` (angles in degrees: φ_i in [0, 360), the
    /// triangle's in (−180, 180]).
    fn values(self, c: &Configuration) -> [f64; 2] {
        match self {
            TriadOutput::Vertex(i) => [c.a[i].x, c.a[i].y],
            TriadOutput::Phi(i) => [c.phi[i].to_degrees(), 0.0],
            TriadOutput::Triangle => [crate::geom::angle_of(c.a[1] - c.a[0]).to_degrees(), 0.0],
        }
    }
}

/// The largest distance between corresponding vertices of two configurations.
fn vertex_distance(a: &[Point; 3], b: &[Point; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).norm()).fold(0.0, f64::max)
}

/// The triad under tolerances: the nominal triad and its assembly modes, the toleranced
/// fields and the watched outputs.
#[derive(Debug, Clone)]
pub struct TriadModel {
    triad: Triad,
    modes: Vec<Configuration>,
    params: Vec<TriadParam>,
    outputs: Vec<TriadOutput>,
    /// Channel values of the nominal, mode-major.
    nominal: Vec<f64>,
    channels: usize,
}

impl TriadModel {
    /// The model of `triad` in its assembly modes `modes` (the scene's, as the run finds
    /// them), with the fields `params` toleranced and `outputs` watched.
    pub fn new(
        triad: Triad,
        modes: Vec<Configuration>,
        params: Vec<TriadParam>,
        outputs: Vec<TriadOutput>,
    ) -> TriadModel {
        let channels = outputs.iter().map(|o| o.channels()).sum();
        let mut nominal = Vec::with_capacity(modes.len() * channels);
        for c in &modes {
            for o in &outputs {
                nominal.extend_from_slice(&o.values(c)[..o.channels()]);
            }
        }
        TriadModel { triad, modes, params, outputs, nominal, channels }
    }

    /// The nominal channel values, mode-major.
    pub fn nominal(&self) -> &[f64] {
        &self.nominal
    }

    /// The watched outputs.
    pub fn outputs(&self) -> &[TriadOutput] {
        &self.outputs
    }

    /// The nominal's assembly modes.
    pub fn modes(&self) -> &[Configuration] {
        &self.modes
    }

    /// The nominal triad.
    pub fn triad(&self) -> &Triad {
        &self.triad
    }

    /// ∂channel/∂field in mode `k`, channel-major (`channels · params` values); `None`
    /// where the three-angle system's Jacobian is singular (see the module's doc).
    pub fn sensitivities(&self, k: usize) -> Option<Vec<f64>> {
        let t = &self.triad;
        let c = &self.modes[k];
        let (_, j) = system(t, &c.phi);
        let e = c.phi.map(|p| {
            let (s, co) = libm::sincos(p);
            Vector::new(co, s)
        });
        let a = c.a;
        // Rows 12, 23, 13: the pair (i, j) and the side.
        let rows = [(0usize, 1usize, t.l12), (1, 2, t.l23), (0, 2, t.l13)];
        let np = self.params.len();
        let mut out = vec![0.0; self.channels * np];
        for (jp, p) in self.params.iter().enumerate() {
            let (da0, dl) = p.direct(&e);
            let mut rhs = [0.0; 3];
            for (r, &(i, jj, l)) in rows.iter().enumerate() {
                let d = (a[i] - a[jj]) / l;
                rhs[r] = -(d.dot(&(da0[i] - da0[jj])) - dl[r]);
            }
            let dphi = solve3(&j, rhs)?;
            let da: [Vector; 3] = std::array::from_fn(|i| da0[i] + perp(e[i]) * (t.r[i] * dphi[i]));
            let mut ch = 0;
            for o in &self.outputs {
                match *o {
                    TriadOutput::Vertex(i) => {
                        out[ch * np + jp] = da[i].x;
                        out[(ch + 1) * np + jp] = da[i].y;
                    }
                    TriadOutput::Phi(i) => out[ch * np + jp] = dphi[i].to_degrees(),
                    TriadOutput::Triangle => {
                        let u = a[1] - a[0];
                        out[ch * np + jp] = (cross(u, da[1] - da[0]) / u.norm_squared()).to_degrees();
                    }
                }
                ch += o.channels();
            }
        }
        Some(out)
    }

    /// The triad `dev` makes of the nominal (`None` when a length is not positive or the
    /// triangle cannot close).
    fn sample_triad(&self, dev: &[f64]) -> Option<Triad> {
        let mut t = self.triad;
        for (p, d) in self.params.iter().zip(dev) {
            p.apply(&mut t, *d);
        }
        Triad::new(t.o, t.r, t.l12, t.l23, t.l13).ok()
    }

    /// Triad `t` solved in nominal mode `k` (Newton from the mode's angles); `None` when it
    /// cannot keep that mode (see the module's doc).
    pub fn solve_mode(&self, t: &Triad, k: usize) -> Option<Configuration> {
        let nominal = &self.modes[k];
        let opts = NewtonOptions { start: nominal.phi, max_iterations: SAMPLE_ITERATIONS };
        let c = newton_to(t, &opts, NEWTON_RESIDUAL_REL).ok()?.configuration;
        if nominal.orientation != Orientation::Collinear && c.orientation != nominal.orientation {
            return None;
        }
        let own = vertex_distance(&c.a, &nominal.a);
        let nearer = self.modes.iter().enumerate().any(|(i, m)| i != k && vertex_distance(&c.a, &m.a) < own);
        (!nearer).then_some(c)
    }

    /// The relative determinant of J (|det J| over its rows' norms' product, in [0, 1]) of
    /// triad `t` in mode `k`, re-solved; `None` where it cannot keep the mode.
    fn relative_determinant(&self, t: &Triad, k: usize) -> Option<f64> {
        let c = self.solve_mode(t, k)?;
        let (_, j) = system(t, &c.phi);
        let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
            + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
        let n = |r: &[f64; 3]| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let norms = n(&j[0]) * n(&j[1]) * n(&j[2]);
        (norms > 0.0).then(|| det.abs() / norms)
    }
}

impl Model for TriadModel {
    type Work = ();

    fn positions(&self) -> usize {
        self.modes.len()
    }

    fn channels(&self) -> usize {
        self.channels
    }

    fn work(&self) {}

    fn evaluate(&self, _: &mut (), dev: &[f64], out: &mut [f64], failed: &mut [bool]) -> bool {
        let Some(t) = self.sample_triad(dev) else {
            failed.iter_mut().for_each(|f| *f = true);
            return true;
        };
        let ch = self.channels;
        let mut any = false;
        for k in 0..self.modes.len() {
            let Some(c) = self.solve_mode(&t, k) else {
                failed[k] = true;
                any = true;
                continue;
            };
            let nominal = &self.nominal[k * ch..(k + 1) * ch];
            let row = &mut out[k * ch..(k + 1) * ch];
            let mut i = 0;
            for o in &self.outputs {
                let v = o.values(&c);
                match o {
                    TriadOutput::Vertex(_) => {
                        row[i] = v[0] - nominal[i];
                        row[i + 1] = v[1] - nominal[i + 1];
                    }
                    _ => row[i] = wrap_deg(v[0] - nominal[i]),
                }
                i += o.channels();
            }
        }
        any
    }
}

impl super::Sensitive for TriadModel {
    fn sensitivities(&self, k: usize) -> Option<Vec<f64>> {
        TriadModel::sensitivities(self, k)
    }

    /// Near the dead point when the tolerances' worst case (shift plus half band, linear in
    /// the relative determinant's central differences) can take more than
    /// [`super::DEAD_POINT_FRACTION`] of the relative determinant of J.
    fn dead_point(&self, k: usize, dims: &[Dimension]) -> Option<String> {
        let rel = self.relative_determinant(&self.triad, k)?;
        let h = DETERMINANT_STEP * self.triad.scale();
        let mut reach = 0.0;
        for (p, d) in self.params.iter().zip(dims) {
            let (mut plus, mut minus) = (self.triad, self.triad);
            p.apply(&mut plus, h);
            p.apply(&mut minus, -h);
            let (Some(a), Some(b)) = (self.relative_determinant(&plus, k), self.relative_determinant(&minus, k)) else {
                return Some("near a dead point: a tolerance step leaves the mode".into());
            };
            reach += ((a - b) / (2.0 * h)).abs() * (d.half() + d.mid().abs());
        }
        (reach > super::DEAD_POINT_FRACTION * rel).then(|| {
            format!(
                "near a dead point: the links O1A1, O2A2, O3A3 are nearly concurrent (J's relative determinant {rel:.3e}) and the tolerances move it by up to {reach:.3e}"
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_round_trip_their_paths() {
        for p in TriadParam::ALL {
            assert_eq!(TriadParam::from_field(&p.field()), Some(p));
        }
        assert_eq!(TriadParam::from_field("o4[0]"), None);
        assert_eq!(TriadOutput::angle("link2"), Some(TriadOutput::Phi(1)));
        assert_eq!(TriadOutput::point("A3"), Some(TriadOutput::Vertex(2)));
        assert_eq!(TriadOutput::point("A4"), None);
        assert_eq!(wrap_deg(359.0), -1.0);
    }
}
