//! Four-bar kinematics (seed 003 and its reference [8]): crank O1A, coupler A–B–M (one
//! rigid ternary link), rocker BC; closed-form RRR dyad for positions, analytic
//! velocities and accelerations.
//!
//! Sign conventions: angles from +x, counter-clockwise positive; phi2 = direction A→B,
//! phi3 = direction C→B; omega and eps counter-clockwise positive (rad/s, rad/s²).
//!
//! (Types fixed by the skeleton so that figures can be written in parallel; the solver
//! functions are filled in by the four-bar kinematics issue.)

use crate::geom::{Point, Side, Vector};

/// Why a four-bar cannot be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FourbarError {
    /// Not implemented yet.
    #[error("the fourbar solver is not implemented yet")]
    NotImplemented,
}

/// Checked geometry of the four-bar (lengths > 0, scene units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Crank pivot O1 (ground).
    pub o1: Point,
    /// Rocker pivot C (ground).
    pub c: Point,
    /// Crank length O1A.
    pub l1: f64,
    /// Coupler side AB.
    pub l_ab: f64,
    /// Coupler side BM.
    pub l_bm: f64,
    /// Angle from ray B→A to ray B→M, counter-clockwise, radians (π: M on AB beyond B).
    pub alpha: f64,
    /// Rocker length BC.
    pub l_bc: f64,
    /// Assembly mode: side of B relative to the directed line A→C.
    pub branch: Side,
}

/// Velocities and accelerations at one crank angle (units/s, units/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Angular velocity of the coupler (link 2), rad/s, CCW positive.
    pub omega2: f64,
    /// Angular velocity of the rocker (link 3).
    pub omega3: f64,
    /// Angular acceleration of the coupler, rad/s².
    pub eps2: f64,
    /// Angular acceleration of the rocker.
    pub eps3: f64,
    /// Velocity of A.
    pub v_a: Vector,
    /// Velocity of B.
    pub v_b: Vector,
    /// Velocity of M.
    pub v_m: Vector,
    /// Velocity of B relative to A (v_B = v_A + v_BA).
    pub v_ba: Vector,
    /// Acceleration of A.
    pub a_a: Vector,
    /// Acceleration of B.
    pub a_b: Vector,
    /// Acceleration of M.
    pub a_m: Vector,
    /// Normal (centripetal) part of a_BA: −omega2²·(B−A).
    pub a_ba_n: Vector,
    /// Tangential part of a_BA: eps2 × (B−A).
    pub a_ba_t: Vector,
    /// Normal part of a_B about C: −omega3²·(B−C).
    pub a_bc_n: Vector,
    /// Tangential part of a_B about C: eps3 × (B−C).
    pub a_bc_t: Vector,
    /// Acceleration of the crank's centroid G1 (middle of O1A).
    pub a_g1: Vector,
    /// Acceleration of the centroid G21 of bar AB (its middle).
    pub a_g21: Vector,
    /// Acceleration of the centroid G22 of bar BM (its middle).
    pub a_g22: Vector,
    /// Acceleration of the rocker's centroid G3 (middle of BC).
    pub a_g3: Vector,
}

/// The four-bar at one crank angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Position {
    /// Crank angle, radians.
    pub phi1: f64,
    /// Crank pin A.
    pub a: Point,
    /// Coupler–rocker joint B.
    pub b: Point,
    /// Coupler point M.
    pub m: Point,
    /// Coupler angle (direction A→B), radians.
    pub phi2: f64,
    /// Rocker angle (direction C→B), radians.
    pub phi3: f64,
    /// Transmission angle (between BA and BC), radians in [0, π].
    pub transmission: f64,
    /// Velocities and accelerations, when the scene asks for them.
    pub kin: Option<Kinematics>,
}
