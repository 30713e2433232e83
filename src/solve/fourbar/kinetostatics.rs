//! Kineto-statics of the four-bar (seed 003): inertia torsors, reactions in the RRR dyad
//! and at the crank, balancing moment.
//!
//! Conventions (design.md §4): R_A = force of link 1 on link 2 at A; R_B = force of link 3
//! on link 2 at B; R_C = force of the ground on link 3 at C; R_O = force of the ground on
//! link 1 at O1; Me1 = balancing (driving) torque on link 1, counter-clockwise positive.
//! Forces in N, torques in N·(scene length unit) (SI scenes: N·m). Gravity acts along −y.
//!
//! Two routes to the same reactions:
//! - [`forces`], the seed's route (eqs. 3–9), which is also what the force polygon draws:
//!   moments about B of link 2 and of link 3 give R_A^n ⊥ AB and R_C^n ⊥ BC; closing the
//!   dyad's force polygon with R_C^t ∥ BC and R_A^t ∥ AB gives their magnitudes; link 2's
//!   polygon gives R_B; the crank's polygon gives R_O and its moments about O1 give Me1.
//! - [`forces_newton_euler`]: all nine unknowns (R_A, R_B, R_C, R_O, Me1) from one 9×9
//!   linear system (Newton–Euler for links 1–3, moments about O1, A and C), solved by LU.
//!
//! By default the bars are homogeneous: centroid at the middle, J = m·l²/12 about it (for
//! every bar, including the rocker: the seed's J3 line forgets m3). A link may give its
//! centroid's offset from the middle and its J ([`LinkMass`]). The coupler is the two bars
//! AB and BM, as in the seed. Besides the coupler forces at A, B, M ([`ExternalForce`]),
//! forces at any point of any link and torques on any link ([`LinkLoad`]) act; gravity is
//! a vector; the crank may have an angular acceleration eps1 ([`Kinematics::eps1`]).

use nalgebra::{SMatrix, SVector};

use super::kinematics::{Kinematics, Position, singular};
use super::{ANGLE_EPS_DEG, FourbarError, Geometry, SINGULAR_SIN};
use crate::geom::{self, Point, Vector, cross, perp};

/// Point of the coupler (link 2) where an external force acts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum ForcePoint {
    /// The crank pin A (the force acts on the coupler there).
    A,
    /// The joint B (the force acts on the coupler there).
    B,
    /// The coupler point M.
    M,
}

impl ForcePoint {
    /// The point at `pos`.
    pub fn at(self, pos: &Position) -> Point {
        match self {
            ForcePoint::A => pos.a,
            ForcePoint::B => pos.b,
            ForcePoint::M => pos.m,
        }
    }
}

/// A closed range of crank angles, degrees, running counter-clockwise from `from_deg` to
/// `to_deg`, both ends included (within [`ANGLE_EPS_DEG`]), compared modulo
/// 360°: `[80, 280]` holds 80° … 280°; `[300, 60]` holds 300° … 360° and 0° … 60°; a range
/// with `to_deg − from_deg ≥ 360` holds every angle; `from_deg = to_deg` one angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrankRange {
    /// Start, degrees.
    pub from_deg: f64,
    /// End (included), degrees.
    pub to_deg: f64,
}

impl CrankRange {
    /// Whether the crank angle `phi1_deg` (any real, degrees) lies in the range.
    pub fn contains_deg(&self, phi1_deg: f64) -> bool {
        let eps = ANGLE_EPS_DEG;
        if self.to_deg - self.from_deg >= 360.0 - eps {
            return true;
        }
        let span = (self.to_deg - self.from_deg).rem_euclid(360.0);
        let x = (phi1_deg - self.from_deg).rem_euclid(360.0);
        x <= span + eps || x >= 360.0 - eps
    }
}

/// A link of the four-bar with its own frame ("link coordinates"): origin at its first
/// point, u along the bar to its second point, v = u turned 90° counter-clockwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Link {
    /// The crank, O1 → A.
    Crank,
    /// The coupler bar A → B.
    Ab,
    /// The coupler bar B → M.
    Bm,
    /// The rocker, C → B.
    Rocker,
}

impl Link {
    /// The four links in the order of [`Dynamics::links`].
    pub const ALL: [Link; 4] = [Link::Crank, Link::Ab, Link::Bm, Link::Rocker];

    /// Index into [`Dynamics::links`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The link's first and second points at `pos`.
    pub fn ends(self, geom: &Geometry, pos: &Position) -> (Point, Point) {
        match self {
            Link::Crank => (geom.o1, pos.a),
            Link::Ab => (pos.a, pos.b),
            Link::Bm => (pos.b, pos.m),
            Link::Rocker => (geom.c, pos.b),
        }
    }

    /// A vector `local` given in link coordinates, in the scene's frame.
    pub fn to_world(self, geom: &Geometry, pos: &Position, local: Vector) -> Vector {
        let (p, q) = self.ends(geom, pos);
        let r = q - p;
        let u = r / r.norm();
        u * local.x + perp(u) * local.y
    }

    /// The angular velocity and acceleration of the link, rad/s and rad/s².
    pub fn motion(self, kin: &Kinematics) -> (f64, f64) {
        match self {
            Link::Crank => (kin.omega1, kin.eps1),
            Link::Ab | Link::Bm => (kin.omega2, kin.eps2),
            Link::Rocker => (kin.omega3, kin.eps3),
        }
    }
}

/// Where a link's mass sits: its centroid's offset from the bar's middle and its moment of
/// inertia. The default is the homogeneous bar (no offset, J = m·l²/12).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LinkMass {
    /// Offset of the centroid from the middle of the bar, in link coordinates (see
    /// [`Link`]), scene length units.
    pub centroid: Vector,
    /// Moment of inertia about the centroid, kg·m² (in every scene); `None`: m·l²/12.
    pub inertia: Option<f64>,
}

/// A force at any point of a link and/or a torque on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkLoad {
    /// The link it acts on.
    pub link: Link,
    /// Point of application in link coordinates (from the link's first point), scene
    /// length units.
    pub at: Vector,
    /// The force, N, in the scene's frame.
    pub force: Vector,
    /// A torque on the link, N·m (in every scene), counter-clockwise positive.
    pub torque: f64,
    /// Crank angles where it acts; `None`: at every angle.
    pub range: Option<CrankRange>,
}

/// An external force on the coupler.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExternalForce {
    /// Where it acts.
    pub at: ForcePoint,
    /// The force, N (in every scene, whatever its length unit).
    pub value: Vector,
    /// Crank angles where it acts; `None`: at every angle.
    pub range: Option<CrankRange>,
}

/// Masses, gravity and external forces, in the units engineers write whatever the scene's
/// length unit: kg, m/s², N. Lengths, velocities and accelerations are in the scene's length
/// unit; the results are forces in N and moments in N·(length unit): N·m in an SI scene,
/// N·mm in a mm scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Dynamics {
    /// Metres per length unit of the geometry (1 for SI, 0.001 for mm): a mass times an
    /// acceleration in length units/s² is `length_unit_m` times a force in N.
    pub length_unit_m: f64,
    /// Gravitational acceleration, m/s² (a scene's scalar g is (0, −g)).
    pub gravity: Vector,
    /// Mass of the crank O1A, kg.
    pub m1: f64,
    /// Mass of the coupler bar AB, kg.
    pub m21: f64,
    /// Mass of the coupler bar BM, kg.
    pub m22: f64,
    /// Mass of the rocker BC, kg.
    pub m3: f64,
    /// External forces on the coupler at A, B, M.
    pub forces: Vec<ExternalForce>,
    /// Centroid offsets and moments of inertia of crank, AB, BM, rocker ([`Link::index`]).
    pub links: [LinkMass; 4],
    /// Forces at any point of any link and torques on any link.
    pub loads: Vec<LinkLoad>,
}

/// Forces at one crank angle: the seed's route, with every vector its force polygon draws.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Forces {
    /// Weight of bar AB (G21).
    pub g21: Vector,
    /// Weight of bar BM (G22).
    pub g22: Vector,
    /// Weight of the rocker (G3).
    pub g3: Vector,
    /// Weight of the crank (G1).
    pub g1: Vector,
    /// Inertia force of bar AB, −m21·a_G21.
    pub fi21: Vector,
    /// Inertia force of bar BM, −m22·a_G22.
    pub fi22: Vector,
    /// Inertia force of the rocker, −m3·a_G3.
    pub fi3: Vector,
    /// Inertia force of the crank, −m1·a_G1.
    pub fi1: Vector,
    /// Inertia moments (−J·eps) of bars AB, BM, rocker, crank; CCW positive.
    pub mi21: f64,
    /// See `mi21`.
    pub mi22: f64,
    /// See `mi21`.
    pub mi3: f64,
    /// See `mi21`.
    pub mi1: f64,
    /// Sum of the external forces acting at this angle (zero outside their range) on the
    /// coupler (the `[[dynamics.force]]` and the link loads on AB and BM).
    pub f_ext: Vector,
    /// Sum of the link loads' forces on the crank at this angle (F1).
    pub f1_ext: Vector,
    /// Sum of the link loads' forces on the rocker at this angle (F3).
    pub f3_ext: Vector,
    /// Component of R_A normal (perpendicular) to AB, from moments about B (seed eq. 3).
    pub r_a_n: Vector,
    /// Component of R_A along the bar AB, from closing the dyad's force polygon (seed eq. 5).
    pub r_a_t: Vector,
    /// Component of R_C normal (perpendicular) to BC, from moments about B (seed eq. 4).
    pub r_c_n: Vector,
    /// Component of R_C along the bar BC, from closing the dyad's force polygon (seed eq. 5).
    pub r_c_t: Vector,
    /// R_A = force of link 1 on link 2 at A.
    pub r_a: Vector,
    /// R_B = force of link 3 on link 2 at B.
    pub r_b: Vector,
    /// R_C = force of the ground on link 3 at C.
    pub r_c: Vector,
    /// R_O = force of the ground on link 1 at O1.
    pub r_o: Vector,
    /// Balancing torque on the crank, CCW positive.
    pub me1: f64,
}

impl Forces {
    /// Whether every component is a finite number (one sum: NaN and infinities propagate).
    pub fn is_finite(&self) -> bool {
        let vectors = [
            self.g21,
            self.g22,
            self.g3,
            self.g1,
            self.fi21,
            self.fi22,
            self.fi3,
            self.fi1,
            self.f_ext,
            self.f1_ext,
            self.f3_ext,
            self.r_a_n,
            self.r_a_t,
            self.r_c_n,
            self.r_c_t,
            self.r_a,
            self.r_b,
            self.r_c,
            self.r_o,
        ];
        let sum: f64 =
            vectors.iter().map(|v| v.x + v.y).sum::<f64>() + self.mi21 + self.mi22 + self.mi3 + self.mi1 + self.me1;
        sum.is_finite()
    }
}

/// The applied (non-reaction) loads at one position: weights, inertia torsors, external
/// forces, with their points of application. Shared by both routes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// Centroids G1 (middle of O1A), G21 (AB), G22 (BM), G3 (BC).
    pub g1_at: Point,
    /// See `g1_at`.
    pub g21_at: Point,
    /// See `g1_at`.
    pub g22_at: Point,
    /// See `g1_at`.
    pub g3_at: Point,
    /// Weights (G1, G21, G22, G3), along −y.
    pub w1: Vector,
    /// See `w1`.
    pub w21: Vector,
    /// See `w1`.
    pub w22: Vector,
    /// See `w1`.
    pub w3: Vector,
    /// Inertia forces −m·a_G.
    pub fi1: Vector,
    /// See `fi1`.
    pub fi21: Vector,
    /// See `fi1`.
    pub fi22: Vector,
    /// See `fi1`.
    pub fi3: Vector,
    /// Inertia moments −J·eps.
    pub mi1: f64,
    /// See `mi1`.
    pub mi21: f64,
    /// See `mi1`.
    pub mi22: f64,
    /// See `mi1`.
    pub mi3: f64,
    /// Sum of the external forces on the coupler acting at this angle.
    pub f_ext: Vector,
    /// Moment of the external forces and torques on the coupler about B.
    pub f_ext_moment_b: f64,
    /// Sum of the external forces on the crank acting at this angle.
    pub f1_ext: Vector,
    /// Moment of the external forces and torques on the crank about O1.
    pub f1_ext_moment_o1: f64,
    /// Sum of the external forces on the rocker acting at this angle.
    pub f3_ext: Vector,
    /// Moment of the external forces and torques on the rocker about B.
    pub f3_ext_moment_b: f64,
}

/// The applied loads at `pos` (crank angle `pos.phi1`).
pub fn loads(geom: &Geometry, pos: &Position, kin: &Kinematics, dynamics: &Dynamics) -> Loads {
    let d = dynamics;
    // Weights m·g in N (g in m/s²); inertia forces m·a and moments J·eps with a in length
    // units/s² and J in kg·(length unit)², times length_unit_m: N and N·(length unit).
    let k = d.length_unit_m;
    let down = d.gravity;
    let phi1_deg = geom::deg(pos.phi1);
    let mut f_ext = Vector::zeros();
    let mut f_ext_moment_b = 0.0;
    for f in &d.forces {
        if f.range.is_none_or(|r| r.contains_deg(phi1_deg)) {
            f_ext += f.value;
            f_ext_moment_b += cross(f.at.at(pos) - pos.b, f.value);
        }
    }
    let (mut f1_ext, mut f1_ext_moment_o1) = (Vector::zeros(), 0.0);
    let (mut f3_ext, mut f3_ext_moment_b) = (Vector::zeros(), 0.0);
    for f in d.loads.iter().filter(|f| f.range.is_none_or(|r| r.contains_deg(phi1_deg))) {
        let (p, _) = f.link.ends(geom, pos);
        let at = p + f.link.to_world(geom, pos, f.at);
        // Torques in N·m, moments here in N·(length unit).
        let torque = f.torque / k;
        match f.link {
            Link::Crank => {
                f1_ext += f.force;
                f1_ext_moment_o1 += cross(at - geom.o1, f.force) + torque;
            }
            Link::Ab | Link::Bm => {
                f_ext += f.force;
                f_ext_moment_b += cross(at - pos.b, f.force) + torque;
            }
            Link::Rocker => {
                f3_ext += f.force;
                f3_ext_moment_b += cross(at - pos.b, f.force) + torque;
            }
        }
    }
    // J in N·(length unit) per rad/s²: k·m·l² for a homogeneous bar, J[kg·m²]/k given.
    let j = |link: Link, m: f64, l: f64| match d.links[link.index()].inertia {
        None => k * m * l * l / 12.0,
        Some(j) => j / k,
    };
    let j1 = j(Link::Crank, d.m1, geom.l1);
    let j21 = j(Link::Ab, d.m21, geom.l_ab);
    let j22 = j(Link::Bm, d.m22, geom.l_bm);
    let j3 = j(Link::Rocker, d.m3, geom.l_bc);
    // A centroid off the middle by `off` (scene frame): a_G = a_mid − ω²·off + ε × off.
    // With no offset both terms are zero and the centroid is the homogeneous bar's.
    let centroid = |link: Link, mid: Point, a_mid: Vector| {
        let off = link.to_world(geom, pos, d.links[link.index()].centroid);
        if off == Vector::zeros() {
            return (mid, a_mid);
        }
        let (w, e) = link.motion(kin);
        (mid + off, a_mid - off * (w * w) + perp(off) * e)
    };
    let (g1_at, a_g1) = centroid(Link::Crank, geom.o1 + (pos.a - geom.o1) * 0.5, kin.a_g1);
    let (g21_at, a_g21) = centroid(Link::Ab, pos.a + (pos.b - pos.a) * 0.5, kin.a_g21);
    let (g22_at, a_g22) = centroid(Link::Bm, pos.b + (pos.m - pos.b) * 0.5, kin.a_g22);
    let (g3_at, a_g3) = centroid(Link::Rocker, geom.c + (pos.b - geom.c) * 0.5, kin.a_g3);
    Loads {
        g1_at,
        g21_at,
        g22_at,
        g3_at,
        w1: down * d.m1,
        w21: down * d.m21,
        w22: down * d.m22,
        w3: down * d.m3,
        fi1: -a_g1 * (k * d.m1),
        fi21: -a_g21 * (k * d.m21),
        fi22: -a_g22 * (k * d.m22),
        fi3: -a_g3 * (k * d.m3),
        // +0 (not −0) at constant speed, as before ε1 was read.
        mi1: if kin.eps1 == 0.0 { 0.0 } else { -j1 * kin.eps1 },
        mi21: -j21 * kin.eps2,
        mi22: -j22 * kin.eps2,
        mi3: -j3 * kin.eps3,
        f_ext,
        f_ext_moment_b,
        f1_ext,
        f1_ext_moment_o1,
        f3_ext,
        f3_ext_moment_b,
    }
}

/// Reactions and balancing moment by the seed's route (eqs. 3–9); see the module docs.
/// Errors with [`FourbarError::Singular`] when A, B, C are collinear (the directions of
/// R_A^t and R_C^t coincide and the force polygon cannot close).
#[inline]
pub fn forces(geom: &Geometry, pos: &Position, kin: &Kinematics, dynamics: &Dynamics) -> Result<Forces, FourbarError> {
    let l = loads(geom, pos, kin, dynamics);
    let b = pos.b;
    let u2 = (pos.b - pos.a) / geom.l_ab; // A→B
    let u3 = (pos.b - geom.c) / geom.l_bc; // C→B
    let s = cross(u2, u3);
    if s.abs() <= SINGULAR_SIN {
        return Err(singular(pos));
    }
    // Eq. 3: link 2, moments about B. R_A^n = k·perp(u2) has moment
    // (A−B) × k·perp(u2) = −l_ab·k about B; the loads' moment K2 balances it: k = K2 / l_ab.
    let k2 =
        cross(l.g21_at - b, l.w21 + l.fi21) + cross(l.g22_at - b, l.w22 + l.fi22) + l.f_ext_moment_b + l.mi21 + l.mi22;
    let r_a_n = perp(u2) * (k2 / geom.l_ab);
    // Eq. 4: link 3, moments about B. R_C^n = k·perp(u3): (C−B) × k·perp(u3) = −l_bc·k.
    let k3 = cross(l.g3_at - b, l.w3 + l.fi3) + l.mi3 + l.f3_ext_moment_b;
    let r_c_n = perp(u3) * (k3 / geom.l_bc);
    // Eq. 5: the dyad's polygon closes with p·u2 (R_A^t) and q·u3 (R_C^t).
    let known = r_a_n + l.w21 + l.fi21 + l.w22 + l.fi22 + l.f_ext + l.w3 + l.fi3 + r_c_n + l.f3_ext;
    let rhs = -known;
    let p = cross(rhs, u3) / s;
    let q = cross(u2, rhs) / s;
    let r_a_t = u2 * p;
    let r_c_t = u3 * q;
    let r_a = r_a_n + r_a_t;
    let r_c = r_c_n + r_c_t;
    // Eq. 7: link 2's polygon.
    let r_b = -(r_a + l.w21 + l.fi21 + l.w22 + l.fi22 + l.f_ext);
    // Eq. 8: link 1 carries −R_A at A: R_O − R_A + G1 + F_i1 + F1 = 0.
    let r_o = r_a - l.w1 - l.fi1 - l.f1_ext;
    // Eq. 9: moments about O1 on link 1:
    // Me1 + (A−O1) × (−R_A) + (G1−O1) × (G1 + F_i1) + M_i1 + M(F1, T1) = 0.
    let me1 = cross(pos.a - geom.o1, r_a) - cross(l.g1_at - geom.o1, l.w1 + l.fi1) - l.mi1 - l.f1_ext_moment_o1;
    Ok(Forces {
        g21: l.w21,
        g22: l.w22,
        g3: l.w3,
        g1: l.w1,
        fi21: l.fi21,
        fi22: l.fi22,
        fi3: l.fi3,
        fi1: l.fi1,
        mi21: l.mi21,
        mi22: l.mi22,
        mi3: l.mi3,
        mi1: l.mi1,
        f_ext: l.f_ext,
        f1_ext: l.f1_ext,
        f3_ext: l.f3_ext,
        r_a_n,
        r_a_t,
        r_c_n,
        r_c_t,
        r_a,
        r_b,
        r_c,
        r_o,
        me1,
    })
}

/// The reactions of the Newton–Euler route: one 9×9 linear system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reactions {
    /// Force of link 1 on link 2 at A.
    pub r_a: Vector,
    /// Force of link 3 on link 2 at B.
    pub r_b: Vector,
    /// Force of the ground on link 3 at C.
    pub r_c: Vector,
    /// Force of the ground on link 1 at O1.
    pub r_o: Vector,
    /// Balancing torque on link 1, CCW positive.
    pub me1: f64,
}

/// The same reactions as [`forces`] from Newton–Euler's equations of links 1–3 solved
/// together (unknowns R_A, R_B, R_C, R_O, Me1; equations: forces of each link, moments of
/// link 1 about O1, link 2 about A, link 3 about C, each with Σ(r_G − P) × m·a_G + J·eps on
/// the inertia side), by LU decomposition.
pub fn forces_newton_euler(
    geom: &Geometry,
    pos: &Position,
    kin: &Kinematics,
    dynamics: &Dynamics,
) -> Result<Reactions, FourbarError> {
    let l = loads(geom, pos, kin, dynamics);
    // Inertia written as [`loads`] gives it: m·a_G = −F_i (N), J·eps = −M_i.
    let (o1, a, b, c) = (geom.o1, pos.a, pos.b, geom.c);
    // Unknown order: R_Ax, R_Ay, R_Bx, R_By, R_Cx, R_Cy, R_Ox, R_Oy, Me1.
    let mut m = SMatrix::<f64, 9, 9>::zeros();
    let mut rhs = SVector::<f64, 9>::zeros();
    // Moment of an unknown force (x, y components at columns i, i+1) applied at r about P:
    // (r−P) × F = rx·Fy − ry·Fx.
    let moment = |m: &mut SMatrix<f64, 9, 9>, row: usize, col: usize, arm: Vector, sign: f64| {
        m[(row, col)] += -arm.y * sign;
        m[(row, col + 1)] += arm.x * sign;
    };
    // Link 1: R_O − R_A + G1 + F1 = m1·a_G1.
    for i in 0..2 {
        m[(i, 6 + i)] = 1.0;
        m[(i, i)] = -1.0;
    }
    let lin1 = -l.fi1 - l.w1 - l.f1_ext;
    rhs[0] = lin1.x;
    rhs[1] = lin1.y;
    // Link 1 about O1: Me1 + (A−O1) × (−R_A) + (G1−O1) × G1 + M(F1, T1) = (G1−O1) × m1·a_G1 + J1·eps1.
    m[(2, 8)] = 1.0;
    moment(&mut m, 2, 0, a - o1, -1.0);
    rhs[2] = cross(l.g1_at - o1, -l.fi1) - l.mi1 - cross(l.g1_at - o1, l.w1) - l.f1_ext_moment_o1;
    // Link 2: R_A + R_B + G21 + G22 + F = m21·a_G21 + m22·a_G22.
    for i in 0..2 {
        m[(3 + i, i)] = 1.0;
        m[(3 + i, 2 + i)] = 1.0;
    }
    let lin2 = -l.fi21 - l.fi22 - l.w21 - l.w22 - l.f_ext;
    rhs[3] = lin2.x;
    rhs[4] = lin2.y;
    // Link 2 about A: (B−A) × R_B + Σ (r−A) × (G, F) + T = Σ (G−A) × m·a_G + (J21 + J22)·eps2.
    moment(&mut m, 5, 2, b - a, 1.0);
    let ext_a = l.f_ext_moment_b + cross(b - a, l.f_ext); // moment about A = about B + (B−A) × ΣF
    rhs[5] = cross(l.g21_at - a, -l.fi21) + cross(l.g22_at - a, -l.fi22)
        - l.mi21
        - l.mi22
        - cross(l.g21_at - a, l.w21)
        - cross(l.g22_at - a, l.w22)
        - ext_a;
    // Link 3: R_C − R_B + G3 + F3 = m3·a_G3.
    for i in 0..2 {
        m[(6 + i, 4 + i)] = 1.0;
        m[(6 + i, 2 + i)] = -1.0;
    }
    let lin3 = -l.fi3 - l.w3 - l.f3_ext;
    rhs[6] = lin3.x;
    rhs[7] = lin3.y;
    // Link 3 about C: (B−C) × (−R_B) + (G3−C) × G3 + M(F3, T3) = (G3−C) × m3·a_G3 + J3·eps3.
    moment(&mut m, 8, 2, b - c, -1.0);
    let ext3_c = l.f3_ext_moment_b + cross(b - c, l.f3_ext);
    rhs[8] = cross(l.g3_at - c, -l.fi3) - l.mi3 - cross(l.g3_at - c, l.w3) - ext3_c;
    let s = cross(b - a, b - c);
    if s.abs() <= SINGULAR_SIN * geom.l_ab * geom.l_bc {
        return Err(singular(pos));
    }
    let x = m.lu().solve(&rhs).ok_or_else(|| singular(pos))?;
    Ok(Reactions {
        r_a: Vector::new(x[0], x[1]),
        r_b: Vector::new(x[2], x[3]),
        r_c: Vector::new(x[4], x[5]),
        r_o: Vector::new(x[6], x[7]),
        me1: x[8],
    })
}
