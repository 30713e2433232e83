//! Kineto-statics of the four-bar (seed 003): inertia torsors, reactions in the RRR dyad
//! and at the crank, balancing moment.
//!
//! Conventions (design.md §4): R_A = force of link 1 on link 2 at A; R_B = force of link 3
//! on link 2 at B; R_C = force of the ground on link 3 at C; R_O = force of the ground on
//! link 1 at O1; Me1 = balancing (driving) torque on link 1, counter-clockwise positive.
//! Forces in N, torques in N·(scene length unit).
//!
//! (Types fixed by the skeleton so that the force figures can be written in parallel; the
//! solver is filled in by the kineto-statics issue.)

use crate::geom::Vector;

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
    /// Sum of the external forces acting at this angle (zero outside their range).
    pub f_ext: Vector,
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
