//! The groups' closed-form velocities and accelerations over [`Real`]: a driven body's
//! directly from its law, a dyad's from its differentiated closures (a 2×2 solved by
//! Cramer's rule, once factored for both). A step computes them on `f64`, a sweep on four
//! steps at a time, with the same operations in the same order (the same bits).

use super::super::lanes::{Real, V2};
use super::forms::{PoseOf, placed};
use super::{Anchor, Attach, DrivenAngle, Mid, Rpr, Rrp, Rrr, Slide};

/// A body's rates read as [`Real`]s: its origin's velocity `v` and acceleration `a`, its
/// angular velocity ω and acceleration ε (counter-clockwise positive).
#[derive(Clone, Copy)]
pub(super) struct RatesOf<T> {
    pub(super) v: V2<T>,
    pub(super) w: T,
    pub(super) a: V2<T>,
    pub(super) e: T,
}

/// What a group's rates read at a step (or four): each body's pose and rates (the bodies
/// solved before the group at this step, and the group's own placed bodies).
pub(super) trait Motions<T: Real> {
    /// Body `b`'s pose.
    fn pose(&self, b: usize) -> PoseOf<T>;
    /// Body `b`'s rates (the group's own are not read).
    fn rates(&self, b: usize) -> RatesOf<T>;

    /// The global position of anchor `a`.
    #[inline(always)]
    fn place(&self, a: Anchor) -> V2<T> {
        placed(self.pose_of(a.body), a.local)
    }

    /// The pose of `a` (`None`: the ground).
    #[inline(always)]
    fn pose_of(&self, a: Attach) -> Option<PoseOf<T>> {
        match a {
            Attach::Ground => None,
            Attach::Body(b) => Some(self.pose(b)),
        }
    }

    /// ω and ε of `a` (zero for the ground).
    #[inline(always)]
    fn spin(&self, a: Attach) -> (T, T) {
        match a {
            Attach::Ground => (T::splat(0.0), T::splat(0.0)),
            Attach::Body(b) => {
                let r = self.rates(b);
                (r.w, r.e)
            }
        }
    }

    /// Velocity and acceleration of the global point `p` carried by `a` (zero on the
    /// ground).
    #[inline(always)]
    fn point_rates(&self, a: Attach, p: V2<T>) -> (V2<T>, V2<T>) {
        let Attach::Body(b) = a else {
            let zero = V2::new(T::splat(0.0), T::splat(0.0));
            return (zero, zero);
        };
        let q = self.rates(b);
        let r = p - self.pose(b).r;
        (q.v + r.perp().scale(q.w), q.a + r.perp().scale(q.e) - r.scale(q.w * q.w))
    }
}

/// The rates of a body at origin `origin` whose global point `p` moves at velocity `vp`
/// with acceleration `ap`, turning at ω = `w`, ε = `e`.
#[inline(always)]
pub(super) fn body_rates<T: Real>(origin: V2<T>, p: V2<T>, (vp, ap): (V2<T>, V2<T>), w: T, e: T) -> RatesOf<T> {
    let r = origin - p;
    RatesOf { v: vp + r.perp().scale(w), w, a: ap + r.perp().scale(e) - r.scale(w * w), e }
}

/// A prismatic joint between an unknown body u and a known one, at the current poses: the
/// global point `p` where the sliding point is, the line's unit direction `w` (global),
/// ω and ε (u's, locked to the known body's), σ = +1 when u slides on the known body's
/// line and −1 when u carries the line, and the velocity `v0` and acceleration `a0` of
/// u's material point at `p` less its sliding terms: that point moves at
/// v0 + σ·ṡ·w and a0 + σ·(2ω·ṡ⊥w + s̈·w), ṡ the sliding speed.
pub(super) struct SlideFrame<T> {
    pub(super) p: V2<T>,
    pub(super) w: V2<T>,
    pub(super) sigma: f64,
    pub(super) omega: T,
    pub(super) eps: T,
    pub(super) v0: V2<T>,
    pub(super) a0: V2<T>,
}

impl<T: Real> SlideFrame<T> {
    /// The slide of `sl` for its unknown body `u`.
    #[inline(always)]
    pub(super) fn of<M: Motions<T>>(m: &M, sl: &Slide, u: usize) -> SlideFrame<T> {
        if sl.u_is_slider {
            let g = sl.q1.body;
            let (omega, eps) = m.spin(g);
            let p = m.place(Anchor { body: Attach::Body(u), local: sl.point.local });
            let (v0, a0) = m.point_rates(g, p);
            let cs = m.pose_of(g).unwrap_or_else(PoseOf::ground).cs();
            SlideFrame { p, w: V2::splat(sl.dir).rot(cs), sigma: 1.0, omega, eps, v0, a0 }
        } else {
            let (omega, eps) = m.spin(sl.point.body);
            let p = m.place(sl.point);
            let (v0, a0) = m.point_rates(sl.point.body, p);
            SlideFrame { p, w: V2::splat(sl.dir).rot(m.pose(u).cs()), sigma: -1.0, omega, eps, v0, a0 }
        }
    }

    /// Velocity and acceleration of u's material point at `p` for sliding speed `sd` and
    /// acceleration `sdd`.
    #[inline(always)]
    pub(super) fn point_rates(&self, sd: T, sdd: T) -> (V2<T>, V2<T>) {
        let sigma = T::splat(self.sigma);
        (
            self.v0 + self.w.scale(sigma * sd),
            self.a0 + (self.w.perp().scale(T::splat(2.0) * self.omega * sd) + self.w.scale(sdd)).scale(sigma),
        )
    }

    /// The line's direction times σ (the sliding speed's column in a dyad's 2×2).
    #[inline(always)]
    pub(super) fn column(&self) -> V2<T> {
        self.w.scale(T::splat(self.sigma))
    }
}

/// The 2×2 system x·c1 + y·c2 = r of a dyad's rates, factored once for the velocities and
/// the accelerations (the same matrix, two right-hand sides): Cramer's rule with 1/det.
#[derive(Clone, Copy)]
pub(super) struct Cramer<T> {
    c1: V2<T>,
    c2: V2<T>,
    inv_det: T,
}

impl<T: Real> Cramer<T> {
    /// The system of columns `c1`, `c2`, and ρ = |det| / (|c1|·|c2|) (the sine of the
    /// angle between the columns: 0 at a dead point).
    #[inline(always)]
    pub(super) fn new(c1: V2<T>, c2: V2<T>) -> (Cramer<T>, T) {
        let det = c1.cross(c2);
        let rho = det.abs() / (c1.norm_squared() * c2.norm_squared()).sqrt();
        (Cramer { c1, c2, inv_det: T::splat(1.0) / det }, rho)
    }

    /// (x, y) for the right-hand side `r`.
    #[inline(always)]
    pub(super) fn solve(&self, r: V2<T>) -> (T, T) {
        (r.cross(self.c2) * self.inv_det, self.c1.cross(r) * self.inv_det)
    }
}

/// A crank's rates: its ω, ε from the law's rates `(d1, d2)` (its first and second time
/// derivatives), its pin's velocity and acceleration.
#[inline(always)]
pub(super) fn crank<T: Real, M: Motions<T>>(c: &DrivenAngle, m: &M, (d1, d2): (T, T)) -> RatesOf<T> {
    let (wr, er) = m.spin(c.reference);
    let k = m.place(c.pin.known);
    let rk = m.point_rates(c.pin.known.body, k);
    let sign = T::splat(c.sign);
    body_rates(m.pose(c.u).r, k, rk, wr + sign * d1, er + sign * d2)
}

/// An RRR dyad's rates: the two bodies' ω, ε from the joint's velocity (and acceleration)
/// closure, a 2×2; and ρ, the 2×2's conditioning.
#[inline(always)]
pub(super) fn rrr<T: Real, M: Motions<T>>(c: &Rrr, m: &M) -> ([RatesOf<T>; 2], T) {
    let (p1, p3) = (m.place(c.k1.known), m.place(c.k3.known));
    let j = m.place(Anchor { body: Attach::Body(c.b1), local: c.a1 });
    let (r1k, r3k) = (m.point_rates(c.k1.known.body, p1), m.point_rates(c.k3.known.body, p3));
    let (r1, r2) = (j - p1, j - p3);
    // v_K1 + ω1⊥r1 = v_K3 + ω2⊥r2, and its derivative.
    let (cr, rho) = Cramer::new(r1.perp(), -r2.perp());
    let (w1, w2) = cr.solve(r3k.0 - r1k.0);
    let rhs = r3k.1 - r1k.1 + r1.scale(w1 * w1) - r2.scale(w2 * w2);
    let (e1, e2) = cr.solve(rhs);
    let o1 = body_rates(m.pose(c.b1).r, p1, r1k, w1, e1);
    ([o1, body_rates(m.pose(c.b2).r, p3, r3k, w2, e2)], rho)
}

/// An RRP dyad's rates: b1's ω, ε and the slider's sliding speed and acceleration, a 2×2;
/// and ρ, its conditioning.
#[inline(always)]
pub(super) fn rrp<T: Real, M: Motions<T>>(c: &Rrp, m: &M) -> ([RatesOf<T>; 2], T) {
    let f = SlideFrame::of(m, &c.s3, c.b2);
    let k = m.place(c.k1.known);
    let rk = m.point_rates(c.k1.known.body, k);
    let j = m.place(Anchor { body: Attach::Body(c.b1), local: c.a1 });
    let (r1, d) = (j - k, j - f.p);
    let (w, e) = (f.omega, f.eps);
    // v_K + ω1⊥r1 = v0 + σ·ṡ·u + ω⊥d (b2 turns with its known body), and its derivative.
    let (cr, rho) = Cramer::new(r1.perp(), (-f.w).scale(T::splat(f.sigma)));
    let (w1, sd) = cr.solve(f.v0 + d.perp().scale(w) - rk.0);
    let (_, a_slide) = f.point_rates(sd, T::splat(0.0));
    let rhs = a_slide + d.perp().scale(e) - d.scale(w * w) - rk.1 + r1.scale(w1 * w1);
    let (e1, sdd) = cr.solve(rhs);
    let o1 = body_rates(m.pose(c.b1).r, k, rk, w1, e1);
    ([o1, body_rates(m.pose(c.b2).r, f.p, f.point_rates(sd, sdd), w, e)], rho)
}

/// An RPR dyad's rates: the common ω, ε and the sliding speed, a 2×2; and ρ, its
/// conditioning.
#[inline(always)]
pub(super) fn rpr<T: Real, M: Motions<T>>(c: &Rpr, m: &M) -> ([RatesOf<T>; 2], T) {
    let (ks, kg, sb, gb) = if c.mid.b1_is_slider { (c.k1, c.k3, c.b1, c.b2) } else { (c.k3, c.k1, c.b2, c.b1) };
    let (ps, pg) = (m.place(ks.known), m.place(kg.known));
    let (rs, rg) = (m.point_rates(ks.known.body, ps), m.point_rates(kg.known.body, pg));
    let dir = V2::splat(-crate::geom::perp(c.mid.n0)).rot(m.pose(gb).cs());
    let dk = pg - ps;
    // Slider and guide turn together about their pivots; P slides along the guide.
    let (cr, rho) = Cramer::new(dk.perp(), -dir);
    let (w, sd) = cr.solve(rg.0 - rs.0);
    let rhs = rg.1 - rs.1 + dk.scale(w * w) + dir.perp().scale(T::splat(2.0) * w * sd);
    let (e, _) = cr.solve(rhs);
    let (os, og) = (body_rates(m.pose(sb).r, ps, rs, w, e), body_rates(m.pose(gb).r, pg, rg, w, e));
    (if c.mid.b1_is_slider { [os, og] } else { [og, os] }, rho)
}

/// A driven slider's rates: its sliding speed and acceleration from the law's rates.
#[inline(always)]
pub(super) fn slider<T: Real, M: Motions<T>>(m: &M, slide: &Slide, u: usize, (d1, d2): (T, T)) -> RatesOf<T> {
    let f = SlideFrame::of(m, slide, u);
    body_rates(m.pose(u).r, f.p, f.point_rates(d1, d2), f.omega, f.eps)
}

/// A PRP dyad's rates: the two sliding speeds and accelerations, a 2×2; and ρ, its
/// conditioning.
#[inline(always)]
pub(super) fn prp<T: Real, M: Motions<T>>(
    m: &M,
    (b1, b2): (usize, usize),
    a1: crate::geom::Vector,
    (s1, s3): (&Slide, &Slide),
) -> ([RatesOf<T>; 2], T) {
    let (f1, f3) = (SlideFrame::of(m, s1, b1), SlideFrame::of(m, s3, b2));
    let j = m.place(Anchor { body: Attach::Body(b1), local: a1 });
    let (d1, d3) = (j - f1.p, j - f3.p);
    let (c1, c3) = (f1.column(), (-f3.w).scale(T::splat(f3.sigma)));
    // v0₁ + σ₁ṡ₁u₁ + ω₁⊥d₁ = v0₃ + σ₃ṡ₃u₃ + ω₃⊥d₃, and its derivative.
    let rhs = f3.v0 + d3.perp().scale(f3.omega) - f1.v0 - d1.perp().scale(f1.omega);
    let (cr, rho) = Cramer::new(c1, c3);
    let (sd1, sd3) = cr.solve(rhs);
    let zero = T::splat(0.0);
    let (_, a1b) = f1.point_rates(sd1, zero);
    let (_, a3b) = f3.point_rates(sd3, zero);
    let rhs = a3b + d3.perp().scale(f3.eps)
        - d3.scale(f3.omega * f3.omega)
        - (a1b + d1.perp().scale(f1.eps) - d1.scale(f1.omega * f1.omega));
    let (sdd1, sdd3) = cr.solve(rhs);
    let o1 = body_rates(m.pose(b1).r, f1.p, f1.point_rates(sd1, sdd1), f1.omega, f1.eps);
    ([o1, body_rates(m.pose(b2).r, f3.p, f3.point_rates(sd3, sdd3), f3.omega, f3.eps)], rho)
}

/// An RPP dyad's rates: the two sliding speeds and accelerations (both bodies turn with
/// the guide's body), a 2×2; and ρ, its conditioning.
#[inline(always)]
pub(super) fn rpp<T: Real, M: Motions<T>>(
    m: &M,
    (b1, b2): (usize, usize),
    k1: super::Pin,
    mid: &Mid,
    s3: &Slide,
) -> ([RatesOf<T>; 2], T) {
    // Both bodies turn with the known body of the guide: ω, ε known; b1 is pinned.
    let f = SlideFrame::of(m, s3, b2);
    let (w, e) = (f.omega, f.eps);
    let k = m.place(k1.known);
    let rk = m.point_rates(k1.known.body, k);
    let (slider, guide, tau) = if mid.b1_is_slider { (b1, b2, 1.0) } else { (b2, b1, -1.0) };
    let pm = m.place(Anchor { body: Attach::Body(slider), local: mid.p });
    let wm = V2::splat(-crate::geom::perp(mid.n0)).rot(m.pose(guide).cs());
    let (rm1, rm3) = (pm - k, pm - f.p);
    let v1 = rk.0 + rm1.perp().scale(w);
    let a1 = rk.1 + rm1.perp().scale(e) - rm1.scale(w * w);
    // v1(Pm) − v2(Pm) = τ·ṡm·um with v2(Pm) = v0 + σ·ṡ·u + ω⊥(Pm − P).
    let (c3, cm) = (f.column(), wm.scale(T::splat(tau)));
    let (cr, rho) = Cramer::new(c3, cm);
    let (sd, sdm) = cr.solve(v1 - f.v0 - rm3.perp().scale(w));
    let (_, a_slide) = f.point_rates(sd, T::splat(0.0));
    let rhs = a1 - a_slide - rm3.perp().scale(e) + rm3.scale(w * w) - wm.perp().scale(T::splat(tau * 2.0) * w * sdm);
    let (sdd, _) = cr.solve(rhs);
    let o1 = body_rates(m.pose(b1).r, k, rk, w, e);
    ([o1, body_rates(m.pose(b2).r, f.p, f.point_rates(sd, sdd), w, e)], rho)
}
