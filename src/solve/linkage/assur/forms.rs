//! The closed forms of the swept kinds (the crank, the RRR, RRP and RPR dyads), stage by
//! stage over [`Real`]: the part of a step that needs no prediction (where the dyad's two
//! roots are), the squared distances of the two roots to the prediction (which root
//! continues the motion), the chosen root's poses, and the turn that keeps a body's angle
//! continuous. A step runs the stages in turn on `f64`; a sweep runs each stage over four
//! steps at a time on [`F4`](super::super::lanes::F4), so both give the same bits.

use super::super::lanes::{Real, V2, compose};

/// A pose read as [`Real`]s: origin, angle, and its (cos, sin).
#[derive(Clone, Copy)]
pub(super) struct PoseOf<T> {
    pub(super) r: V2<T>,
    pub(super) phi: T,
    pub(super) c: T,
    pub(super) s: T,
}

impl<T: Real> PoseOf<T> {
    /// The ground's pose (origin 0, angle 0) in every lane.
    #[inline(always)]
    pub(super) fn ground() -> PoseOf<T> {
        let (z, one) = (T::splat(0.0), T::splat(1.0));
        PoseOf { r: V2::new(z, z), phi: z, c: one, s: z }
    }
    /// The rotation (cos, sin).
    #[inline(always)]
    pub(super) fn cs(&self) -> (T, T) {
        (self.c, self.s)
    }
}

/// The global position of the point `local` of a body at pose `p` (`None`: the ground,
/// whose points are their own coordinates plus 0 — what R + A(φ)·s gives at R = 0, φ = 0,
/// a −0 becoming +0 as there, without the rotation).
#[inline(always)]
pub(super) fn placed<T: Real>(p: Option<PoseOf<T>>, local: crate::geom::Vector) -> V2<T> {
    match p {
        None => V2::splat(crate::geom::Vector::new(local.x + 0.0, local.y + 0.0)),
        Some(p) => p.r + V2::splat(local).rot(p.cs()),
    }
}

/// The rotation taking `from` to `to` when 1/(|from|·|to|) = `inv_lengths`.
#[inline(always)]
pub(super) fn rotation_scaled<T: Real>(from: V2<T>, to: V2<T>, inv_lengths: T) -> (T, T) {
    (from.dot(to) * inv_lengths, from.cross(to) * inv_lengths)
}

/// atan x = x − x³/3 + x⁵/5 − …, the first seven terms (|x| ≤ 1/16: the first term left
/// out, x¹⁵/15, is under 2^-56 of x, below half an ulp).
const ATAN_SERIES: [f64; 7] = [1.0, -1.0 / 3.0, 1.0 / 5.0, -1.0 / 7.0, 1.0 / 9.0, -1.0 / 11.0, 1.0 / 13.0];

/// The angle of the vector (c, s) by the short series of a small angle (the ratio s/c: the
/// length cancels), and where the series holds (c > 0, |s| ≤ c/16): elsewhere the angle is
/// `atan2(s, c)`, which [`turn_angle`] takes.
#[inline(always)]
pub(super) fn turn_series<T: Real>(c: T, s: T) -> (T, T::Mask) {
    let x = s / c;
    let k = |i: usize| T::splat(ATAN_SERIES[i]);
    let x2 = x * x;
    let x4 = x2 * x2;
    // Estrin's scheme: the pairs, then the pairs of pairs, are independent (a shorter chain
    // of dependent operations than Horner's rule, for the same terms).
    let (p01, p23, p45) = (k(0) + k(1) * x2, k(2) + k(3) * x2, k(4) + k(5) * x2);
    let p0123 = p01 + p23 * x4;
    let p456 = p45 + k(6) * x4;
    let holds = c.gt(T::splat(0.0)) & s.abs().le(T::splat(0.0625) * c);
    (x * (p0123 + p456 * (x4 * x4)), holds)
}

/// The angle in (−π, π] of the vector (c, s) (any length, not both zero): a short series
/// for a small angle, `atan2` for a larger one.
#[inline(always)]
pub(super) fn turn_angle(c: f64, s: f64) -> f64 {
    let (t, holds) = turn_series(c, s);
    if holds { t } else { libm::atan2(s, c) }
}

/// The rotation `last` turned by a predicted change `d` of its angle, through a short
/// series (errors below |d|⁷/5040 < 2e-6: the prediction only chooses a dyad's root, it is
/// never part of a result). A predicted turn over 0.5 rad is not trusted (a time step too
/// coarse for the motion extrapolates to any angle): `last` itself is the guess then.
#[inline(always)]
pub(super) fn predicted_turn<T: Real>(last: (T, T), d: T) -> (T, T) {
    let d2 = d * d;
    let one = T::splat(1.0);
    // Multiplications by the reciprocals (no division; an ulp of difference is nothing
    // against the series' own error).
    let (k720, k120) = (T::splat(1.0 / 720.0), T::splat(1.0 / 120.0));
    let turn = (
        one - d2 * (T::splat(0.5) - d2 * (T::splat(1.0 / 24.0) - d2 * k720)),
        d * (one - d2 * (T::splat(1.0 / 6.0) - d2 * k120)),
    );
    let turned = compose(last, turn);
    let trusted = d.abs().le(T::splat(0.5));
    (T::select(trusted, turned.0, last.0), T::select(trusted, turned.1, last.1))
}

/// The vector whose angle is the turn of a body's `arm` (body coordinates) from where its
/// last rotation `last` pointed it to the global direction `v` it points now: (was·v,
/// was × v), for [`turn_series`].
#[inline(always)]
pub(super) fn arm_turn<T: Real>(last: (T, T), arm: crate::geom::Vector, v: V2<T>) -> (T, T) {
    let was = V2::splat(arm).rot(last);
    (was.dot(v), was.cross(v))
}

/// The vector whose angle is the turn from rotation `from` to rotation `to`.
#[inline(always)]
pub(super) fn rotation_turn<T: Real>(from: (T, T), to: (T, T)) -> (T, T) {
    (to.0 * from.0 + to.1 * from.1, to.1 * from.0 - to.0 * from.1)
}

/// The constants of an RRR dyad's closed form (its links' lengths d1, d2, their squares and
/// reciprocal squares, the closure's slack).
#[derive(Debug, Clone, Copy)]
pub(super) struct RrrForm {
    pub(super) d1: f64,
    pub(super) d1sq: f64,
    pub(super) d2sq: f64,
    pub(super) inv_d1sq: f64,
    pub(super) inv_d2sq: f64,
}

/// Where an RRR dyad's two roots are: the joint is m ± off (`+`: the first root), h² the
/// squared half-chord; `ok` where the circles about the pivots p1, p3 meet (a miss within
/// `slack` counts as a tangency, a dead point).
#[derive(Clone, Copy)]
pub(super) struct Chord<T: Real> {
    pub(super) m: V2<T>,
    pub(super) off: V2<T>,
    pub(super) h2: T,
    pub(super) ok: T::Mask,
}

/// An RRR dyad's roots about its pivots `p1`, `p3`: one division and one square root on
/// the way to the joint (as the four-bar's dyad): the foot of the chord at k·dv from p1
/// (k = a/d), the half-chord h·e⊥ = (h/d)·dv⊥.
#[inline(always)]
pub(super) fn rrr_chord<T: Real>(c: &RrrForm, p1: V2<T>, p3: V2<T>, slack: f64) -> Chord<T> {
    let dv = p3 - p1;
    let dsq = dv.norm_squared();
    let inv_dsq = T::splat(1.0) / dsq;
    let k = T::splat(0.5) * (T::splat(1.0) + T::splat(c.d1sq - c.d2sq) * inv_dsq);
    let h2 = T::splat(c.d1sq) - k * k * dsq;
    let zero = T::splat(0.0);
    let h2 = T::select(h2.lt(zero) & h2.ge(T::splat(-2.0 * c.d1 * slack)), zero, h2);
    let ok = h2.ge(zero) & dsq.gt(zero);
    let off = dv.perp().scale((h2 * inv_dsq).sqrt());
    Chord { m: p1 + dv.scale(k), off, h2, ok }
}

/// The squared distances of an RRR dyad's two roots to where b1's predicted rotation
/// `pred` puts the joint (|m ± off − jp|² = |jp − m|² + h² ∓ 2·off·(jp − m)).
#[inline(always)]
pub(super) fn rrr_distances<T: Real>(
    (m, off, h2): (V2<T>, V2<T>, T),
    p1: V2<T>,
    pred: (T, T),
    arm1: crate::geom::Vector,
) -> (T, T) {
    let dd = p1 + V2::splat(arm1).rot(pred) - m;
    let (common, x) = (dd.norm_squared() + h2, T::splat(2.0) * off.dot(dd));
    (common - x, common + x)
}

/// An RRR dyad's bodies at the root `root` (+1 the first, −1 the second): each link's
/// rotation, origin, and the direction from its pivot to the joint (|j − p1| = d1 and
/// |j − p3| = d2 by construction: no square roots).
#[derive(Clone, Copy)]
pub(super) struct RrrPoses<T> {
    pub(super) c1: (T, T),
    pub(super) c2: (T, T),
    pub(super) r1: V2<T>,
    pub(super) r2: V2<T>,
    pub(super) v1: V2<T>,
    pub(super) v3: V2<T>,
}

/// An RRR dyad's poses at a root (see [`RrrPoses`]): `arm1`, `arm3` the links' arms (pivot
/// to joint, body coordinates), `k1`, `k3` the pivots' points on the links.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn rrr_poses<T: Real>(
    c: &RrrForm,
    ch: &Chord<T>,
    root: T,
    p1: V2<T>,
    p3: V2<T>,
    (arm1, arm3): (crate::geom::Vector, crate::geom::Vector),
    (k1, k3): (crate::geom::Vector, crate::geom::Vector),
) -> RrrPoses<T> {
    let j = ch.m + ch.off.scale(root);
    let (v1, v3) = (j - p1, j - p3);
    let c1 = rotation_scaled(V2::splat(arm1), v1, T::splat(c.inv_d1sq));
    let c2 = rotation_scaled(V2::splat(arm3), v3, T::splat(c.inv_d2sq));
    RrrPoses { c1, c2, r1: p1 - V2::splat(k1).rot(c1), r2: p3 - V2::splat(k3).rot(c2), v1, v3 }
}

/// A line a body's origin runs on, c + s·w, with the body's angle, its (cos, sin) (locked
/// to a known body's through a prismatic joint).
#[derive(Clone, Copy)]
pub(super) struct LineOf<T> {
    pub(super) phi: T,
    pub(super) cs: (T, T),
    pub(super) c: V2<T>,
    pub(super) w: V2<T>,
}

/// Where an RRP dyad's two roots are along its slider's line: s = −b ± √disc (`+` the
/// first root) from the joint's base point `base` (the slider's joint at s = 0); `ok` where
/// the circle about the pivot meets the line (a miss within `slack` counts as a tangency).
#[derive(Clone, Copy)]
pub(super) struct Reach<T: Real> {
    pub(super) base: V2<T>,
    pub(super) b: T,
    pub(super) root: T,
    pub(super) ok: T::Mask,
}

/// An RRP dyad's roots: its pivot `p1` (link b1 of length `d1`), its slider b2 on `line`
/// carrying the joint at `a2` (body coordinates).
#[inline(always)]
pub(super) fn rrp_reach<T: Real>(
    p1: V2<T>,
    line: &LineOf<T>,
    a2: crate::geom::Vector,
    (d1, d1sq): (f64, f64),
    slack: f64,
) -> Reach<T> {
    let base = line.c + V2::splat(a2).rot(line.cs);
    let e = base - p1;
    let b = e.dot(line.w);
    let disc = b * b - e.norm_squared() + T::splat(d1sq);
    let zero = T::splat(0.0);
    let disc = T::select(disc.lt(zero) & disc.ge(T::splat(-2.0 * d1 * slack)), zero, disc);
    Reach { base, b, root: disc.sqrt(), ok: disc.ge(zero) }
}

/// The sliding distances of an RRP dyad's two roots, and their squared distances to b2's
/// predicted origin `rp` (at s_p = (rp − c)·w along the line and |rp − c|² − s_p² off it).
#[inline(always)]
pub(super) fn rrp_distances<T: Real>((b, root): (T, T), (c, w): (V2<T>, V2<T>), rp: V2<T>) -> ((T, T), (T, T)) {
    let off = rp - c;
    let sp = off.dot(w);
    let across = off.norm_squared() - sp * sp;
    let (sv0, sv1) = (-b + root, -b - root);
    ((sv0, sv1), ((sv0 - sp) * (sv0 - sp) + across, (sv1 - sp) * (sv1 - sp) + across))
}

/// An RRP dyad's poses at the sliding distance `sv`: b1's rotation, origin and the
/// direction from its pivot to the joint; b2's origin (its angle is the line's).
#[inline(always)]
pub(super) fn rrp_poses<T: Real>(
    re: &Reach<T>,
    line: &LineOf<T>,
    sv: T,
    p1: V2<T>,
    (arm1, inv_d1sq, k1): (crate::geom::Vector, f64, crate::geom::Vector),
) -> ((T, T), V2<T>, V2<T>, V2<T>) {
    let j = re.base + line.w.scale(sv);
    let v1 = j - p1;
    let c1 = rotation_scaled(V2::splat(arm1), v1, T::splat(inv_d1sq));
    (c1, p1 - V2::splat(k1).rot(c1), v1, line.c + line.w.scale(sv))
}

/// The constants of an RPR dyad's closed form: the guide's normal n0 (guide body
/// coordinates), the slider's turn against the guide, c0 = n0 · (rot(turn)·(p − k_S) −
/// (q1 − k_G)) (the guide's offset from the slider's pivot).
#[derive(Debug, Clone, Copy)]
pub(super) struct RprForm {
    pub(super) n0: crate::geom::Vector,
    pub(super) turn: (f64, f64),
    pub(super) c0: f64,
    pub(super) b1_is_slider: bool,
}

/// Where an RPR dyad's two roots are: the guide's normal n_G = along ± across (`+` the
/// first root), unit vectors with n_G·D̂ = −c0/|D| (D from the guide's pivot `kg` to the
/// slider's `ks`); `ok` where the guide can reach the slider's pivot (|c0| ≤ |D|, or within
/// `slack` of it: the guide then passes through the pivot).
#[derive(Clone, Copy)]
pub(super) struct Normal<T: Real> {
    pub(super) along: V2<T>,
    pub(super) across: V2<T>,
    pub(super) ok: T::Mask,
}

/// An RPR dyad's roots: (−c0·D ± √(|D|² − c0²)·D⊥)/|D|² (one division and one square
/// root, independent).
#[inline(always)]
pub(super) fn rpr_normal<T: Real>(c: &RprForm, ks: V2<T>, kg: V2<T>, slack: f64) -> Normal<T> {
    let zero = T::splat(0.0);
    let c0 = T::splat(c.c0);
    let dv = ks - kg;
    let dsq = dv.norm_squared();
    let inside = dsq.gt(zero) & (c0 * c0).le(dsq);
    let d = dsq.sqrt();
    let passes = d.gt(zero) & c0.abs().le(d + T::splat(slack));
    let c0 = T::select(inside, c0, T::splat(c.c0.signum()) * d);
    let inv_dsq = T::splat(1.0) / dsq;
    let along = dv.scale(-c0 * inv_dsq);
    let gap = dsq - c0 * c0;
    let gap = T::select(gap.gt(zero), gap, zero);
    Normal { along, across: dv.perp().scale(gap.sqrt() * inv_dsq), ok: inside | passes }
}

/// The squared distances of an RPR dyad's two guide normals to the normal at the guide's
/// predicted rotation `pred`.
#[inline(always)]
pub(super) fn rpr_distances<T: Real>(c: &RprForm, (along, across): (V2<T>, V2<T>), pred: (T, T)) -> (T, T) {
    let u = along - V2::splat(c.n0).rot(pred);
    let (common, cross_term) = (u.norm_squared() + across.norm_squared(), T::splat(2.0) * across.dot(u));
    (common + cross_term, common - cross_term)
}

/// An RPR dyad's rotations at the root `root` (+1 the first, −1 the second): b1's and
/// b2's (slider and guide turn together).
#[inline(always)]
pub(super) fn rpr_rotations<T: Real>(c: &RprForm, nm: &Normal<T>, root: T) -> ((T, T), (T, T)) {
    let ng = nm.along + nm.across.scale(root);
    let n0 = V2::splat(c.n0);
    let cg = (n0.dot(ng), n0.cross(ng));
    let cs = compose(cg, (T::splat(c.turn.0), T::splat(c.turn.1)));
    if c.b1_is_slider { (cs, cg) } else { (cg, cs) }
}

impl From<super::Pose> for PoseOf<f64> {
    #[inline(always)]
    fn from(p: super::Pose) -> PoseOf<f64> {
        PoseOf { r: p.r.into(), phi: p.phi, c: p.c, s: p.s }
    }
}
