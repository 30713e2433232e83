//! The Assur route's sweep: each group solved over every time step of a motion before the
//! next group ([`AssurSolver::positions_into`], [`AssurSolver::motion_into`]). A group needs
//! only the groups before it at the same step, its own last two positions (its prediction)
//! and its branch, so a sweep holds each group's constants across the steps and gives the
//! bits of stepping.
//!
//! The crank and the RRR, RRP and RPR dyads are solved four steps at a time ([`Batch`]): a
//! dyad's root at a step depends on its prediction, which depends on the roots before it,
//! so the sweep first places every step on the branch the group is on (the roots need no
//! prediction then), solves their rates (with the rates), then checks each step's choice as
//! the step makes it ([`choose`], from the prediction of the positions and rates just
//! solved) and places the rest again from the first step that changes branch (at a dead
//! point). The closed forms' stages are the step's own ([`forms`], [`rates`], over
//! [`Real`]), so every lane holds the step's bits. The other kinds are swept a step at a
//! time through a [`Lane`], by the step's closed forms themselves.

use super::super::lanes::{F4, Lanes, Real, V2};
use super::forms::{self, PoseOf};
use super::rates;
use super::*;

/// Whether steps are taken four at once ([`F4`], the lanes of SIMD registers): on the command
/// line. The browser's module takes them one at a time: the same bits (each lane computes
/// what one step computes), a little slower, and without a four-lane copy of every dyad
/// kind's placing, turning, rates and flips (the sweep was ~190 KB of the module's code).
const FOUR: bool = !cfg!(target_arch = "wasm32");

/// A body's fields in [`Tracks`]: its pose (x, y, φ, cos φ, sin φ), its rates (ẋ, ẏ, ω from
/// `QD`) and their derivatives (ẍ, ÿ, ε from `QDD`).
const X: usize = 0;
const Y: usize = 1;
const PHI: usize = 2;
const COS: usize = 3;
const SIN: usize = 4;
const QD: usize = 5;
const QDD: usize = 8;
const FIELDS: usize = 11;

/// Every body's poses and rates over a sweep's steps, body by body and field by field (see
/// [`X`]…[`QDD`]): body b's field f at entry i at `bodies[b][f·stride + i]`, step k at entry
/// k + 2 (entries 0 and 1 hold the step before the last and the last; the rates of the step
/// before the last are not kept). Each body its own buffer, so that a batch writes its
/// group's bodies while it reads the bodies before them.
#[derive(Debug, Clone, Default)]
struct Tracks {
    bodies: Vec<Vec<f64>>,
    stride: usize,
}

impl Tracks {
    /// Room for `bodies` over `steps` (not cleared: a group reads only what the sweep has
    /// written — the first two entries of each body, the steps the groups before it solved,
    /// its own last steps — so the buffers only grow).
    fn reset(&mut self, bodies: usize, steps: usize) {
        self.stride = steps + 2;
        if self.bodies.len() < bodies {
            self.bodies.resize_with(bodies, Vec::new);
        }
        for v in &mut self.bodies {
            if v.len() < FIELDS * self.stride {
                v.resize(FIELDS * self.stride, 0.0);
            }
        }
    }

    /// Field `f` of body `b` at entry `i`.
    #[inline(always)]
    fn get(&self, b: usize, f: usize, i: usize) -> f64 {
        self.bodies[b][f * self.stride + i]
    }

    /// Body `b`'s pose at entry `i`.
    #[inline(always)]
    fn pose(&self, b: usize, i: usize) -> Pose {
        let f = |f| self.get(b, f, i);
        Pose { r: Vector::new(f(X), f(Y)), phi: f(PHI), c: f(COS), s: f(SIN) }
    }

    /// Body `b`'s rates at entry `i`.
    #[inline(always)]
    fn rates(&self, b: usize, i: usize) -> Rates {
        let f = |f| self.get(b, f, i);
        Rates { qd: [f(QD), f(QD + 1), f(QD + 2)], qdd: [f(QDD), f(QDD + 1), f(QDD + 2)] }
    }

    #[inline(always)]
    fn set_rates(&mut self, b: usize, i: usize, r: Rates) {
        let stride = self.stride;
        let v = &mut self.bodies[b];
        for j in 0..3 {
            v[(QD + j) * stride + i] = r.qd[j];
            v[(QDD + j) * stride + i] = r.qdd[j];
        }
    }

    #[inline(always)]
    fn set(&mut self, b: usize, i: usize, p: Pose) {
        let stride = self.stride;
        let v = &mut self.bodies[b];
        for (f, x) in [(X, p.r.x), (Y, p.r.y), (PHI, p.phi), (COS, p.c), (SIN, p.s)] {
            v[f * stride + i] = x;
        }
    }
}

/// Step `k` of a sweep ([`AssurSolver::positions_into`], [`AssurSolver::motion_into`]):
/// the sweep's poses and rates ([`Tracks`]), the laws' values (and rates) at each step, the
/// steps' predictions. A [`Batch`] kind reads it four steps at a time.
struct Lane<'a> {
    tracks: &'a mut Tracks,
    k: usize,
    /// The laws' jets step by step (driver d's at step k at `k·nd + d`; with the rates).
    jets: &'a [(f64, f64, f64)],
    nd: usize,
    how: Extrapolation,
    /// Each step's ratio of linear extrapolation, NaN where it is not linear.
    linear: &'a [f64],
    /// Each step's time step for Taylor's prediction, NaN where it is not Taylor's.
    taylor: &'a [f64],
    /// Driver d's law value at step k at `d·count + k` (`count` the times asked for).
    values: &'a [f64],
    count: usize,
    /// The steps swept (the scratch planes' length).
    steps: usize,
    /// The motion's rows from the sweep's first step (q, and with the rates q̇, q̈; `n`
    /// values a step), written as the poses and rates are.
    q: &'a mut [f64],
    qd: &'a mut [f64],
    qdd: &'a mut [f64],
    n: usize,
    /// A batch's scratch planes, [`SCRATCH`] of `steps` values (see [`Io`]).
    scratch: &'a mut [f64],
}

impl Poses for Lane<'_> {
    #[inline(always)]
    fn pose(&self, b: usize) -> Pose {
        self.tracks.pose(b, self.k + 2)
    }
}

impl Lane<'_> {
    /// The prediction of coordinate `j` (0: x, 1: y, 2: φ) of body `b`, as
    /// [`Predictor::at`] gives it (the two entries before step 0 hold the q of the step
    /// before the last and of the last; Taylor's rates are the last step's).
    #[inline(always)]
    fn predicted(&self, b: usize, j: usize) -> f64 {
        let (tr, k) = (&*self.tracks, self.k);
        self.how.apply(
            tr.get(b, j, k + 1),
            || tr.get(b, j, k),
            || (tr.get(b, QD + j, k + 1), tr.get(b, QDD + j, k + 1)),
        )
    }
}

impl Frame for Lane<'_> {
    #[inline(always)]
    fn last(&self, b: usize) -> Pose {
        self.tracks.pose(b, self.k + 1)
    }
    #[inline(always)]
    fn law(&self, d: usize) -> f64 {
        self.values[d * self.count + self.k]
    }
    #[inline(always)]
    fn predicted_phi(&self, b: usize) -> f64 {
        self.predicted(b, 2)
    }
    #[inline(always)]
    fn predicted_r(&self, b: usize) -> Vector {
        Vector::new(self.predicted(b, 0), self.predicted(b, 1))
    }
    #[inline(always)]
    fn put(&mut self, b: usize, r: Vector, phi: f64, cs: (f64, f64)) {
        self.tracks.set(b, self.k + 2, Pose { r, phi, c: cs.0, s: cs.1 });
        let at = self.k * self.n + 3 * b;
        self.q[at..at + 3].copy_from_slice(&[r.x, r.y, phi]);
    }
}

impl RateFrame for Lane<'_> {
    #[inline(always)]
    fn rates(&self, b: usize) -> Rates {
        self.tracks.rates(b, self.k + 2)
    }
    #[inline(always)]
    fn jet(&self, d: usize) -> (f64, f64, f64) {
        self.jets[self.k * self.nd + d]
    }
    #[inline(always)]
    fn put_rates(&mut self, b: usize, r: Rates) {
        self.tracks.set_rates(b, self.k + 2, r);
        let at = self.k * self.n + 3 * b;
        self.qd[at..at + 3].copy_from_slice(&r.qd);
        self.qdd[at..at + 3].copy_from_slice(&r.qdd);
    }
}

/// A sweep's buffers (kept between sweeps): every body's poses and rates over the steps
/// (see [`Lane`]), the laws' values (and rates) and the prediction of each step, each
/// group's branch and (with rates) the conditioning of its rates after each step, a
/// batch's scratch.
#[derive(Debug, Clone, Default)]
pub(super) struct Sweep {
    tracks: Tracks,
    jets: Vec<(f64, f64, f64)>,
    values: Vec<f64>,
    how: Vec<Extrapolation>,
    linear: Vec<f64>,
    taylor: Vec<f64>,
    sides: Vec<f64>,
    pivots: Vec<f64>,
    scratch: Vec<f64>,
}

/// Whether ρ, a group's conditioning at a step, lets its rates be solved there.
#[inline(always)]
fn solvable(rho: Option<f64>) -> Option<f64> {
    rho.filter(|rho| !(rho.is_nan() || *rho <= super::super::SINGULAR_PIVOT_REL))
}

/// One group over the sweep's steps `0..end`, its kind's closed form `K` at each (and, with
/// `RATES`, its rates, whose conditioning goes into `pivots`), its position's constants
/// and branch held across the steps: the first step it cannot solve (stepped alone
/// afterwards, which says why: a position that cannot be assembled, rates at a dead
/// point).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn sweep_group<const RATES: bool, K: Kernel>(
    op: &mut Op,
    mut lane: Lane<'_>,
    how: &[Extrapolation],
    sides: &mut [f64],
    pivots: &mut [f64],
    end: usize,
    slack: f64,
) -> Option<usize> {
    let position = op.position.clone();
    let mut side = op.side;
    for (k, (&how, after)) in how[..end].iter().zip(&mut sides[..end]).enumerate() {
        lane.k = k;
        lane.how = how;
        if K::position(&mut lane, &position, &mut side, slack).is_err() {
            op.side = side;
            return Some(k);
        }
        *after = side;
        if RATES {
            match solvable(K::rates(&mut lane, &position)) {
                Some(rho) => pivots[k] = rho,
                None => {
                    op.side = side;
                    return Some(k);
                }
            }
        }
    }
    op.side = side;
    None
}

/// A kind's closed forms for a sweep's loop: its position and its rates at a step (static
/// calls, inlined into the loop of each kind).
trait Kernel {
    /// The group's position at the lane's step.
    fn position(lane: &mut Lane<'_>, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why>;
    /// The group's rates at the lane's step: ρ, the conditioning of its 2×2.
    fn rates(lane: &mut Lane<'_>, position: &Position) -> Option<f64>;
}

/// The [`Kernel`] of each kind: `Type => position's closed form, rates' closed form`.
macro_rules! kernels {
    ($($name:ident => $position:ident, $rates:ident;)*) => {$(
        impl Kernel for $name {
            #[inline(always)]
            fn position(lane: &mut Lane<'_>, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
                $position(lane, position, side, slack)
            }
            #[inline(always)]
            fn rates(lane: &mut Lane<'_>, position: &Position) -> Option<f64> {
                $rates(lane, position)
            }
        }
    )*};
}

/// The kinds swept a step at a time (the others are their [`Batch`] constants).
struct DrivenDistanceK;
struct PrpK;
struct RppK;

kernels! {
    DrivenAngle => driven_angle, driven_angle_rates;
    DrivenDistanceK => driven_distance, driven_distance_rates;
    Rrr => rrr, rrr_rates;
    Rrp => rrp, rrp_rates;
    Rpr => rpr, rpr_rates;
    PrpK => prp, prp_rates;
    RppK => rpp, rpp_rates;
}

/// A body's fields over a batch's range of steps `from..to`: entries `from..to + 2` of each
/// (index c + 2 is step from + c, c + 1 and c the two steps before it).
type Planes<'a> = [&'a [f64]; FIELDS];

/// What a [`Batch`] kind reads and writes over a range of steps, each slice cut to the range
/// (so that the loops' indices are within every bound by construction): the known bodies it
/// reads and its own bodies (poses and rates), by the roles its [`Roles`] give them, its
/// law's values and the laws' jets, each step's linear ratio and Taylor's time step, the
/// scratch planes it keeps from its positions for its turns and choices, and the motion's
/// rows.
struct Io<'a> {
    /// The known bodies (`None`: the ground).
    known: [Option<Planes<'a>>; 2],
    /// The group's bodies (an absent one's slices empty).
    own: [[&'a mut [f64]; FIELDS]; 2],
    law: &'a [f64],
    /// The laws' jets step by step (`nd` a step; with the rates).
    jets: &'a [(f64, f64, f64)],
    nd: usize,
    linear: &'a [f64],
    taylor: &'a [f64],
    scratch: [&'a mut [f64]; SCRATCH],
    /// The motion's rows over the range (q, and with the rates q̇, q̈), `n` values a step.
    q: &'a mut [f64],
    qd: &'a mut [f64],
    qdd: &'a mut [f64],
    n: usize,
}

/// Scratch planes a batch keeps from its positions for its turns and its choices.
const SCRATCH: usize = 11;

/// The bodies a [`Batch`] kind reads and writes: the known bodies of its two roles (the
/// ground, or a body solved before its group), its own bodies (the second absent for a
/// crank), which of them keep a continued angle by a turn, and its law.
struct Roles {
    known: [Attach; 2],
    own: [Option<usize>; 2],
    turned: [bool; 2],
    law: Option<usize>,
}

impl Roles {
    /// A dyad pinned to its known bodies at `k1` and `k3`, both its bodies' angles continued
    /// by turns.
    fn pivoted(k1: Pin, k3: Pin, [b1, b2]: [usize; 2]) -> Roles {
        Roles { known: [k1.known.body, k3.known.body], own: [Some(b1), Some(b2)], turned: [true; 2], law: None }
    }
}

/// A dyad kind's constants out of its [`Position`] ([`Batch::of`]).
macro_rules! dyad_of {
    ($kind:ident) => {
        fn of(p: &Position) -> $kind {
            let Position::$kind(c) = p else { unreachable!(concat!("a dyad ", stringify!($kind))) };
            *c
        }
    };
}

impl Io<'_> {
    /// The pose of known role `r` at index `i` (`None`: the ground).
    #[inline(always)]
    fn known_pose<T: Lanes>(&self, r: usize, i: usize) -> Option<PoseOf<T>> {
        let p = self.known[r]?;
        let f = |f: usize| T::load(&p[f][i..i + T::N]);
        Some(PoseOf { r: V2::new(f(X), f(Y)), phi: f(PHI), c: f(COS), s: f(SIN) })
    }

    /// The global position of the point `local` of known role `r` at step c.
    #[inline(always)]
    fn place<T: Lanes>(&self, r: usize, local: Vector, c: usize) -> V2<T> {
        match self.known[r] {
            None => forms::placed(None, local),
            Some(p) => {
                let f = |f: usize| T::load(&p[f][c + 2..c + 2 + T::N]);
                let pose = PoseOf { r: V2::new(f(X), f(Y)), phi: T::splat(0.0), c: f(COS), s: f(SIN) };
                forms::placed(Some(pose), local)
            }
        }
    }

    /// Field `f` of own role `r` at index `i`.
    #[inline(always)]
    fn own<T: Lanes>(&self, r: usize, f: usize, i: usize) -> T {
        T::load(&self.own[r][f][i..i + T::N])
    }

    /// Writes fields of own role `r` at step c.
    #[inline(always)]
    fn put<T: Lanes, const F: usize>(&mut self, r: usize, c: usize, fields: [(usize, T); F]) {
        for (f, v) in fields {
            v.store(&mut self.own[r][f][c + 2..c + 2 + T::N]);
        }
    }

    /// The rotation of own role `r` at index `i`.
    #[inline(always)]
    fn rotation<T: Lanes>(&self, r: usize, i: usize) -> (T, T) {
        (self.own(r, COS, i), self.own(r, SIN, i))
    }

    /// Scratch plane `p` at step c.
    #[inline(always)]
    fn kept<T: Lanes>(&self, p: usize, c: usize) -> T {
        T::load(&self.scratch[p][c..c + T::N])
    }

    #[inline(always)]
    fn keep<T: Lanes>(&mut self, p: usize, c: usize, v: T) {
        v.store(&mut self.scratch[p][c..c + T::N]);
    }

    #[inline(always)]
    fn kept2<T: Lanes>(&self, p: usize, c: usize) -> V2<T> {
        V2::new(self.kept(p, c), self.kept(p + 1, c))
    }

    #[inline(always)]
    fn keep2<T: Lanes>(&mut self, p: usize, c: usize, v: V2<T>) {
        self.keep(p, c, v.x);
        self.keep(p + 1, c, v.y);
    }

    /// The prediction of coordinate `j` of own role `r` at steps c.., each predicted
    /// linearly, as [`Lane::predicted`] gives it.
    #[inline(always)]
    fn predicted_linearly<T: Lanes>(&self, r: usize, j: usize, c: usize) -> T {
        let now: T = self.own(r, j, c + 1);
        now + (now - self.own(r, j, c)) * T::load(&self.linear[c..c + T::N])
    }

    /// The prediction of coordinate `j` of own role `r` at steps c.., each predicted by
    /// Taylor from the rates of the step before, as [`Lane::predicted`] gives it.
    #[inline(always)]
    fn predicted_by_rates<T: Lanes>(&self, r: usize, j: usize, c: usize) -> T {
        let now: T = self.own(r, j, c + 1);
        let (v, a): (T, T) = (self.own(r, QD + j, c + 1), self.own(r, QDD + j, c + 1));
        let dt = T::load(&self.taylor[c..c + T::N]);
        now + v * dt + T::splat(0.5) * a * dt * dt
    }

    /// The prediction of coordinate `j` of own role `r` at step c by `how`, as
    /// [`Lane::predicted`] gives it.
    #[inline(always)]
    fn predicted(&self, r: usize, j: usize, c: usize, how: Extrapolation) -> f64 {
        let own = &self.own[r];
        how.apply(own[j][c + 1], || own[j][c], || (own[QD + j][c + 1], own[QDD + j][c + 1]))
    }
}

impl Lane<'_> {
    /// Runs `f` on the [`Io`] of `roles` over steps `from..to`: the own bodies' buffers taken
    /// out of the tracks meanwhile (the known ones are read in place), and the rows of
    /// the motion.
    fn with_io<R>(&mut self, roles: &Roles, from: usize, to: usize, f: impl FnOnce(&mut Io<'_>) -> R) -> R {
        let stride = self.tracks.stride;
        let mut taken = roles.own.map(|b| b.map(|b| std::mem::take(&mut self.tracks.bodies[b])).unwrap_or_default());
        let result = {
            let bodies = &self.tracks.bodies;
            let known = roles.known.map(|a| match a {
                Attach::Ground => None,
                Attach::Body(b) => {
                    let v = &bodies[b][..];
                    Some(std::array::from_fn(|f| &v[f * stride + from..f * stride + to + 2]))
                }
            });
            let [a, b] = &mut taken;
            let own = [a, b].map(|v| {
                let mut rest = &mut v[..];
                std::array::from_fn(|_| {
                    if rest.len() < stride {
                        return &mut [][..];
                    }
                    let (plane, tail) = std::mem::take(&mut rest).split_at_mut(stride);
                    rest = tail;
                    &mut plane[from..to + 2]
                })
            });
            let law = roles.law.map_or(&[][..], |d| &self.values[d * self.count + from..d * self.count + to]);
            let mut rest = &mut self.scratch[..];
            let steps = self.steps;
            let scratch = std::array::from_fn(|_| {
                let (plane, tail) = std::mem::take(&mut rest).split_at_mut(steps);
                rest = tail;
                &mut plane[from..to]
            });
            let n = self.n;
            let mut io = Io {
                known,
                own,
                law,
                jets: if self.jets.is_empty() { &[] } else { &self.jets[from * self.nd..to * self.nd] },
                nd: self.nd,
                linear: &self.linear[from..to],
                taylor: &self.taylor[from..to],
                scratch,
                q: &mut self.q[from * n..to * n],
                qd: if self.qd.is_empty() { &mut [] } else { &mut self.qd[from * n..to * n] },
                qdd: if self.qdd.is_empty() { &mut [] } else { &mut self.qdd[from * n..to * n] },
                n,
            };
            f(&mut io)
        };
        for (b, v) in roles.own.iter().zip(taken) {
            if let Some(b) = *b {
                self.tracks.bodies[b] = v;
            }
        }
        result
    }
}

/// A kind a sweep solves four steps at a time: its closed form's stages ([`forms`]) over
/// [`Lanes`] of steps, from its constants (`Self`, copied out of its [`Position`]), on the
/// bodies of its [`Roles`] through an [`Io`] (step from + c at index c).
trait Batch: Kernel + Copy {
    /// Whether the kind chooses between two roots (a crank has one).
    const ROOTS: bool;
    /// The kind's constants in `p`.
    fn of(p: &Position) -> Self;
    /// The bodies it reads and writes.
    fn roles(&self) -> Roles;
    /// Positions at steps c.. (T::N of them) on the branch `side`: the poses the step's
    /// closed form puts, but for the angles continued by a turn, whose φ entries get the
    /// turn later ([`Batch::turn`]); the lanes where the closed form finds a position.
    fn place<T: Lanes>(&self, io: &mut Io<'_>, c: usize, side: f64, slack: f64) -> T::Mask;
    /// The turns at steps c.., into the φ entries of the own bodies [`Roles::turned`] names
    /// (their last angles added by [`place_range`]).
    fn turn<T: Lanes>(&self, io: &mut Io<'_>, c: usize);
    /// The rates of its own bodies at steps c.. (their poses placed, the bodies before them
    /// solved), and ρ, the conditioning of its 2×2 (1 for a driven body).
    fn rates<T: Lanes>(&self, m: &At<'_>) -> ([rates::RatesOf<T>; 2], T);
    /// Which of steps c.. would take the other root than `side` ([`choose`]'s rule), each
    /// from its prediction `pred(role, coordinate)` of the positions placed before it.
    fn flips<T: Lanes>(&self, io: &Io<'_>, c: usize, side: f64, pred: impl Fn(usize, usize) -> T) -> T::Mask;
}

/// The lanes where [`choose`] at squared distances `d0`, `d1` takes the other root than the
/// branch `side` (+1: the first, −1: the second; never 0 here).
#[inline(always)]
fn flipped<T: Real>(d0: T, d1: T, side: f64) -> T::Mask {
    let sixteen = T::splat(16.0);
    let first = d0.le(d1 / sixteen);
    if side > 0.0 { !first & d1.le(d0 / sixteen) } else { first }
}

/// Positions of steps `from..to` of a [`Batch`] kind on the branch `side`: placed four
/// steps at a time, then the turns, then the angles and the motion's rows. Returns the
/// first step it cannot place (`to`: none).
fn place_range<K: Batch>(l: &mut Lane<'_>, kind: K, from: usize, to: usize, side: f64, slack: f64) -> usize {
    let roles = kind.roles();
    l.with_io(&roles, from, to, |io| {
        let steps = to - from;
        let mut end = steps;
        let mut c = 0;
        while FOUR && c + F4::N <= steps {
            if let Some(i) = F4::first_false(kind.place::<F4>(io, c, side, slack)) {
                end = c + i;
                break;
            }
            c += F4::N;
        }
        if end == steps {
            while c < steps {
                if !kind.place::<f64>(io, c, side, slack) {
                    end = c;
                    break;
                }
                c += 1;
            }
        }
        let mut c = 0;
        while FOUR && c + F4::N <= end {
            kind.turn::<F4>(io, c);
            c += F4::N;
        }
        for c in c..end {
            kind.turn::<f64>(io, c);
        }
        // Each turned body's angle: the last one plus its turn, summed in a register (through
        // memory, each sum would wait on the store before it); every body's row of the
        // motion.
        let n = io.n;
        for ((own, b), turned) in io.own.iter_mut().zip(roles.own).zip(roles.turned) {
            let Some(b) = b else { continue };
            let [x, y, phi, ..] = own;
            let (x, y, (last, phi)) = (&x[2..end + 2], &y[2..end + 2], phi[1..end + 2].split_at_mut(1));
            let rows = io.q.chunks_exact_mut(n).map(|row| &mut row[3 * b..3 * b + 3]);
            let mut angle = last[0];
            for (((row, &x), &y), phi) in rows.zip(x).zip(y).zip(phi) {
                if turned {
                    angle += *phi;
                    *phi = angle;
                }
                row.copy_from_slice(&[x, y, *phi]);
            }
        }
        from + end
    })
}

/// A batch's [`Io`] read as [`rates::Motions`] at step c: its bodies by their roles.
struct At<'a> {
    io: &'a Io<'a>,
    roles: &'a Roles,
    c: usize,
}

impl At<'_> {
    /// Body `b`'s fields (one of the roles' bodies).
    #[inline(always)]
    fn body(&self, b: usize) -> Planes<'_> {
        let (io, roles) = (self.io, self.roles);
        for r in 0..2 {
            if roles.own[r] == Some(b) {
                let own = &io.own[r];
                return std::array::from_fn(|f| &own[f][..]);
            }
        }
        for r in 0..2 {
            if let (Attach::Body(k), Some(p)) = (roles.known[r], io.known[r])
                && k == b
            {
                return p;
            }
        }
        unreachable!("body {b} is not one of the group's roles")
    }

    /// Field `f` of `planes` at steps c...
    #[inline(always)]
    fn at<T: Lanes>(&self, planes: &Planes<'_>, f: usize) -> T {
        let i = self.c + 2;
        T::load(&planes[f][i..i + T::N])
    }

    /// Driver `d`'s first and second time derivatives at steps c...
    #[inline(always)]
    fn law_rates<T: Lanes>(&self, d: usize) -> (T, T) {
        let (jets, nd, c) = (self.io.jets, self.io.nd, self.c);
        (T::gather(|i| jets[(c + i) * nd + d].1), T::gather(|i| jets[(c + i) * nd + d].2))
    }
}

impl<T: Lanes> rates::Motions<T> for At<'_> {
    #[inline(always)]
    fn pose(&self, b: usize) -> PoseOf<T> {
        let p = self.body(b);
        let f = |f| self.at(&p, f);
        PoseOf { r: V2::new(f(X), f(Y)), phi: f(PHI), c: f(COS), s: f(SIN) }
    }
    #[inline(always)]
    fn rates(&self, b: usize) -> rates::RatesOf<T> {
        let p = self.body(b);
        let f = |f| self.at(&p, f);
        rates::RatesOf { v: V2::new(f(QD), f(QD + 1)), w: f(QD + 2), a: V2::new(f(QDD), f(QDD + 1)), e: f(QDD + 2) }
    }
}

/// The rates of steps `from..to` of a [`Batch`] kind (positions placed), four steps at a
/// time, each step's conditioning into `pivots`: the first step whose rates cannot be
/// solved (a dead point; `to`: none), before which every step's rates are in the tracks and
/// the motion's rows.
fn rates_range<K: Batch>(l: &mut Lane<'_>, kind: K, from: usize, to: usize, pivots: &mut [f64]) -> usize {
    let roles = kind.roles();
    l.with_io(&roles, from, to, |io| {
        let steps = to - from;
        let pivots = &mut pivots[from..to];
        let mut end = steps;
        let mut c = 0;
        while c < steps {
            let four = FOUR && c + F4::N <= steps;
            let bad = if four {
                rates_at_c::<K, F4>(kind, io, &roles, c, pivots)
            } else {
                rates_at_c::<K, f64>(kind, io, &roles, c, pivots)
            };
            if let Some(i) = bad {
                end = c + i;
                break;
            }
            c += if four { F4::N } else { 1 };
        }
        let n = io.n;
        for (own, b) in io.own.iter().zip(roles.own) {
            let Some(b) = b else { continue };
            for (rows, at) in [(&mut *io.qd, QD), (&mut *io.qdd, QDD)] {
                let (x, y, w) = (&own[at][2..end + 2], &own[at + 1][2..end + 2], &own[at + 2][2..end + 2]);
                let rows = rows.chunks_exact_mut(n).map(|row| &mut row[3 * b..3 * b + 3]);
                for (((row, &x), &y), &w) in rows.zip(x).zip(y).zip(w) {
                    row.copy_from_slice(&[x, y, w]);
                }
            }
        }
        from + end
    })
}

/// The rates of a [`Batch`] kind at steps c.. into its own bodies' tracks, each step's ρ
/// into `pivots`: the first lane where they cannot be solved.
#[inline(always)]
fn rates_at_c<K: Batch, T: Lanes>(
    kind: K,
    io: &mut Io<'_>,
    roles: &Roles,
    c: usize,
    pivots: &mut [f64],
) -> Option<usize> {
    let (out, rho) = kind.rates::<T>(&At { io, roles, c });
    for (r, o) in out.into_iter().enumerate() {
        if roles.own[r].is_none() {
            continue;
        }
        let put = |io: &mut Io<'_>, f: usize, v: T| v.store(&mut io.own[r][f][c + 2..c + 2 + T::N]);
        for (f, v) in [(QD, o.v.x), (QD + 1, o.v.y), (QD + 2, o.w), (QDD, o.a.x), (QDD + 1, o.a.y), (QDD + 2, o.e)] {
            put(io, f, v);
        }
    }
    rho.store(&mut pivots[c..c + T::N]);
    // As `solvable`: not NaN and above the singular pivot.
    T::first_false(rho.gt(T::splat(super::super::SINGULAR_PIVOT_REL)))
}

/// One group of a [`Batch`] kind over the sweep's steps `0..end`, as [`sweep_group`]
/// solves it: its positions placed on the branch it is on, then (with `RATES`) its rates
/// solved, then each step's choice checked; where a step takes the other root, the steps
/// from it are placed again on that branch.
#[allow(clippy::too_many_arguments)]
fn sweep_batch<const RATES: bool, K: Batch>(
    op: &mut Op,
    mut l: Lane<'_>,
    how: &[Extrapolation],
    sides: &mut [f64],
    pivots: &mut [f64],
    end: usize,
    slack: f64,
) -> Option<usize> {
    let p = op.position.clone();
    let kind = K::of(&p);
    let mut side = op.side;
    let mut from = 0;
    // No branch yet (the first step after the assembly): that step chooses by the step's
    // own closed form.
    if K::ROOTS && side == 0.0 && end > 0 {
        l.how = how[0];
        if K::position(&mut l, &p, &mut side, slack).is_err() || (RATES && !rates_at::<K>(&mut l, &p, pivots)) {
            op.side = side;
            return Some(0);
        }
        sides[0] = side;
        from = 1;
    }
    let placed = place_range(&mut l, kind, from, end, side, slack);
    let stop = (placed < end).then_some(placed);
    // The steps whose choice is checked (`from..checked`) and whose rates are solved
    // (`from..rated`): a step's check reads the rates of the step before it (Taylor's
    // prediction), so the rates go first, up to the first step where they cannot be solved.
    let (mut checked, mut rated) = (from, from);
    loop {
        let mut failed = None;
        if RATES && rated < placed {
            let solved = rates_range(&mut l, kind, rated, placed, pivots);
            failed = (solved < placed).then_some(solved);
        }
        let limit = failed.map_or(placed, |f| f + 1);
        let flip = if K::ROOTS { first_flip(&mut l, kind, checked, limit, side, how) } else { None };
        let Some(at) = flip else {
            sides[checked..limit].fill(side);
            if failed.is_some() {
                op.side = side;
                return failed;
            }
            break;
        };
        // The step takes the other root (its choice is decided whatever the branch): it
        // and the steps after it are placed again on that branch.
        sides[checked..at].fill(side);
        side = -side;
        place_range(&mut l, kind, at, placed, side, slack);
        sides[at] = side;
        (checked, rated) = (at + 1, at);
    }
    op.side = side;
    stop
}

/// The first of steps `from..to` (placed, with the rates their predictions read) whose
/// choice takes the other root than `side`: four steps at once where each is predicted
/// linearly, or each by Taylor, else one.
fn first_flip<K: Batch>(
    l: &mut Lane<'_>,
    kind: K,
    from: usize,
    to: usize,
    side: f64,
    how: &[Extrapolation],
) -> Option<usize> {
    let roles = kind.roles();
    l.with_io(&roles, from, to, |io| {
        let (io, steps) = (&*io, to - from);
        let mut c = 0;
        while c < steps {
            let four = FOUR && c + F4::N <= steps;
            let flip = if four && io.linear[c..c + F4::N].iter().all(|f| !f.is_nan()) {
                F4::first_true(kind.flips::<F4>(io, c, side, |r, j| io.predicted_linearly(r, j, c)))
            } else if four && io.taylor[c..c + F4::N].iter().all(|f| !f.is_nan()) {
                F4::first_true(kind.flips::<F4>(io, c, side, |r, j| io.predicted_by_rates(r, j, c)))
            } else {
                let how = how[from + c];
                let flip = kind.flips::<f64>(io, c, side, |r, j| io.predicted(r, j, c, how));
                c += 1;
                if flip {
                    return Some(from + c - 1);
                }
                continue;
            };
            if let Some(i) = flip {
                return Some(from + c + i);
            }
            c += F4::N;
        }
        None
    })
}

/// The rates of a [`Batch`] kind at the lane's step, their conditioning into `pivots`:
/// whether they could be solved.
#[inline(always)]
fn rates_at<K: Kernel>(l: &mut Lane<'_>, p: &Position, pivots: &mut [f64]) -> bool {
    match solvable(K::rates(l, p)) {
        Some(rho) => {
            pivots[l.k] = rho;
            true
        }
        None => false,
    }
}

/// The turn whose vector is (c, s) (see [`forms::turn_series`]): the series, `atan2` where
/// it does not hold.
#[inline(always)]
fn turn_of<T: Lanes>((c, s): (T, T)) -> T {
    let (t, holds) = forms::turn_series(c, s);
    t.patch(holds, |i| libm::atan2(s.lane(i), c.lane(i)))
}

/// Own role `r`'s predicted rotation at steps c.., from `pred`, the prediction of its angle
/// (as the step's `predicted_rotation`).
#[inline(always)]
fn predicted_rotation_at<T: Lanes>(io: &Io<'_>, r: usize, c: usize, pred: T) -> (T, T) {
    let last_phi: T = io.own(r, PHI, c + 1);
    forms::predicted_turn(io.rotation(r, c + 1), pred - last_phi)
}

/// The known body a slide's line turns with.
fn line_body(s: &Slide) -> Attach {
    if s.u_is_slider { s.q1.body } else { s.point.body }
}

impl Batch for DrivenAngle {
    const ROOTS: bool = false;
    fn of(p: &Position) -> DrivenAngle {
        let Position::DrivenAngle(c) = p else { unreachable!("a crank") };
        *c
    }
    fn roles(&self) -> Roles {
        Roles {
            known: [self.pin.known.body, self.reference],
            own: [Some(self.u), None],
            turned: [false; 2],
            law: Some(self.law),
        }
    }
    #[inline(always)]
    fn rates<T: Lanes>(&self, m: &At<'_>) -> ([rates::RatesOf<T>; 2], T) {
        let r = rates::crank(self, m, m.law_rates(self.law));
        ([r, r], T::splat(1.0))
    }
    #[inline(always)]
    fn place<T: Lanes>(&self, io: &mut Io<'_>, c: usize, _: f64, _: f64) -> T::Mask {
        let reference = io.known_pose::<T>(1, c + 2).unwrap_or_else(PoseOf::ground);
        let phi = reference.phi + T::splat(self.sign) * T::load(&io.law[c..c + T::N]);
        // One argument reduction for both (the same bits as libm's sin and cos), a step at
        // a time.
        let (sn, cn) = phi.map2(libm::sincos);
        let r = io.place::<T>(0, self.pin.known.local, c) - V2::splat(self.pin.local).rot((cn, sn));
        io.put(0, c, [(X, r.x), (Y, r.y), (PHI, phi), (COS, cn), (SIN, sn)]);
        T::mask(true)
    }
    #[inline(always)]
    fn turn<T: Lanes>(&self, _: &mut Io<'_>, _: usize) {}
    #[inline(always)]
    fn flips<T: Lanes>(&self, _: &Io<'_>, _: usize, _: f64, _: impl Fn(usize, usize) -> T) -> T::Mask {
        T::mask(false)
    }
}

/// An RRR dyad's scratch planes: the directions from its pivots to the joint (its turns),
/// its first pivot, the chord's foot, offset and h² (its choices).
const RRR_V1: usize = 0;
const RRR_V3: usize = 2;
const RRR_P1: usize = 4;
const RRR_M: usize = 6;
const RRR_OFF: usize = 8;
const RRR_H2: usize = 10;

impl Batch for Rrr {
    const ROOTS: bool = true;
    dyad_of!(Rrr);
    fn roles(&self) -> Roles {
        Roles::pivoted(self.k1, self.k3, [self.b1, self.b2])
    }
    #[inline(always)]
    fn rates<T: Lanes>(&self, m: &At<'_>) -> ([rates::RatesOf<T>; 2], T) {
        rates::rrr(self, m)
    }
    #[inline(always)]
    fn place<T: Lanes>(&self, io: &mut Io<'_>, c: usize, side: f64, slack: f64) -> T::Mask {
        let (p1, p3) = (io.place::<T>(0, self.k1.known.local, c), io.place::<T>(1, self.k3.known.local, c));
        let ch = forms::rrr_chord(&self.form, p1, p3, slack);
        let at = forms::rrr_poses(
            &self.form,
            &ch,
            T::splat(side),
            p1,
            p3,
            (self.arm1, self.arm3),
            (self.k1.local, self.k3.local),
        );
        io.put(0, c, [(X, at.r1.x), (Y, at.r1.y), (COS, at.c1.0), (SIN, at.c1.1)]);
        io.put(1, c, [(X, at.r2.x), (Y, at.r2.y), (COS, at.c2.0), (SIN, at.c2.1)]);
        io.keep2(RRR_V1, c, at.v1);
        io.keep2(RRR_V3, c, at.v3);
        io.keep2(RRR_P1, c, p1);
        io.keep2(RRR_M, c, ch.m);
        io.keep2(RRR_OFF, c, ch.off);
        io.keep(RRR_H2, c, ch.h2);
        ch.ok
    }
    #[inline(always)]
    fn turn<T: Lanes>(&self, io: &mut Io<'_>, c: usize) {
        for (r, v, arm) in [(0, RRR_V1, self.arm1), (1, RRR_V3, self.arm3)] {
            let t = turn_of(forms::arm_turn(io.rotation::<T>(r, c + 1), arm, io.kept2(v, c)));
            t.store(&mut io.own[r][PHI][c + 2..c + 2 + T::N]);
        }
    }
    #[inline(always)]
    fn flips<T: Lanes>(&self, io: &Io<'_>, c: usize, side: f64, pred: impl Fn(usize, usize) -> T) -> T::Mask {
        let chord = (io.kept2(RRR_M, c), io.kept2(RRR_OFF, c), io.kept(RRR_H2, c));
        let predicted = predicted_rotation_at(io, 0, c, pred(0, PHI));
        let (d0, d1) = forms::rrr_distances(chord, io.kept2(RRR_P1, c), predicted, self.arm1);
        flipped(d0, d1, side)
    }
}

/// An RRP dyad's scratch planes: the direction from its pivot to the joint (its turns); its
/// roots' sliding distance and half-spread, its line's origin and direction (its choices).
const RRP_V1: usize = 0;
const RRP_B: usize = 2;
const RRP_ROOT: usize = 3;
const RRP_C: usize = 4;
const RRP_W: usize = 6;

impl Batch for Rrp {
    const ROOTS: bool = true;
    dyad_of!(Rrp);
    fn roles(&self) -> Roles {
        Roles {
            known: [self.k1.known.body, line_body(&self.s3)],
            own: [Some(self.b1), Some(self.b2)],
            turned: [true, false],
            law: None,
        }
    }
    #[inline(always)]
    fn rates<T: Lanes>(&self, m: &At<'_>) -> ([rates::RatesOf<T>; 2], T) {
        rates::rrp(self, m)
    }
    #[inline(always)]
    fn place<T: Lanes>(&self, io: &mut Io<'_>, c: usize, side: f64, slack: f64) -> T::Mask {
        let p1 = io.place::<T>(0, self.k1.known.local, c);
        let line = self.s3.line_at(io.known_pose(1, c + 2));
        let reach = forms::rrp_reach(p1, &line, self.a2, (self.d1, self.d1sq), slack);
        let sv = if side > 0.0 { -reach.b + reach.root } else { -reach.b - reach.root };
        let (c1, r1, v1, r2) = forms::rrp_poses(&reach, &line, sv, p1, (self.arm1, self.inv_d1sq, self.k1.local));
        io.put(0, c, [(X, r1.x), (Y, r1.y), (COS, c1.0), (SIN, c1.1)]);
        io.put(1, c, [(X, r2.x), (Y, r2.y), (PHI, line.phi), (COS, line.cs.0), (SIN, line.cs.1)]);
        io.keep2(RRP_V1, c, v1);
        io.keep(RRP_B, c, reach.b);
        io.keep(RRP_ROOT, c, reach.root);
        io.keep2(RRP_C, c, line.c);
        io.keep2(RRP_W, c, line.w);
        reach.ok
    }
    #[inline(always)]
    fn turn<T: Lanes>(&self, io: &mut Io<'_>, c: usize) {
        let t = turn_of(forms::arm_turn(io.rotation::<T>(0, c + 1), self.arm1, io.kept2(RRP_V1, c)));
        t.store(&mut io.own[0][PHI][c + 2..c + 2 + T::N]);
    }
    #[inline(always)]
    fn flips<T: Lanes>(&self, io: &Io<'_>, c: usize, side: f64, pred: impl Fn(usize, usize) -> T) -> T::Mask {
        let (roots, line) = ((io.kept(RRP_B, c), io.kept(RRP_ROOT, c)), (io.kept2(RRP_C, c), io.kept2(RRP_W, c)));
        let (_, (e0, e1)) = forms::rrp_distances(roots, line, V2::new(pred(1, X), pred(1, Y)));
        flipped(e0, e1, side)
    }
}

/// An RPR dyad's scratch planes: the guide normal's two parts (its choices).
const RPR_ALONG: usize = 0;
const RPR_ACROSS: usize = 2;

impl Batch for Rpr {
    const ROOTS: bool = true;
    dyad_of!(Rpr);
    fn roles(&self) -> Roles {
        Roles::pivoted(self.k1, self.k3, [self.b1, self.b2])
    }
    #[inline(always)]
    fn rates<T: Lanes>(&self, m: &At<'_>) -> ([rates::RatesOf<T>; 2], T) {
        rates::rpr(self, m)
    }
    #[inline(always)]
    fn place<T: Lanes>(&self, io: &mut Io<'_>, c: usize, side: f64, slack: f64) -> T::Mask {
        let (p1, p3) = (io.place::<T>(0, self.k1.known.local, c), io.place::<T>(1, self.k3.known.local, c));
        let (ks, kg) = if self.form.b1_is_slider { (p1, p3) } else { (p3, p1) };
        let normal = forms::rpr_normal(&self.form, ks, kg, slack);
        let (c1, c2) = forms::rpr_rotations(&self.form, &normal, T::splat(side));
        let (r1, r2) = (p1 - V2::splat(self.k1.local).rot(c1), p3 - V2::splat(self.k3.local).rot(c2));
        io.put(0, c, [(X, r1.x), (Y, r1.y), (COS, c1.0), (SIN, c1.1)]);
        io.put(1, c, [(X, r2.x), (Y, r2.y), (COS, c2.0), (SIN, c2.1)]);
        io.keep2(RPR_ALONG, c, normal.along);
        io.keep2(RPR_ACROSS, c, normal.across);
        normal.ok
    }
    #[inline(always)]
    fn turn<T: Lanes>(&self, io: &mut Io<'_>, c: usize) {
        // Slider and guide turn together: one turn, b1's, continues both angles.
        let t = turn_of(forms::rotation_turn(io.rotation::<T>(0, c + 1), io.rotation(0, c + 2)));
        t.store(&mut io.own[0][PHI][c + 2..c + 2 + T::N]);
        t.store(&mut io.own[1][PHI][c + 2..c + 2 + T::N]);
    }
    #[inline(always)]
    fn flips<T: Lanes>(&self, io: &Io<'_>, c: usize, side: f64, pred: impl Fn(usize, usize) -> T) -> T::Mask {
        let normal = (io.kept2(RPR_ALONG, c), io.kept2(RPR_ACROSS, c));
        let guide = if self.form.b1_is_slider { 1 } else { 0 };
        let (d0, d1) = forms::rpr_distances(&self.form, normal, predicted_rotation_at(io, guide, c, pred(guide, PHI)));
        flipped(d0, d1, side)
    }
}

/// One group swept: a [`Batch`] kind four steps at a time ([`sweep_batch`]), another kind a
/// step at a time ([`sweep_group`]).
fn sweep_kind<const RATES: bool>(
    op: &mut Op,
    lane: Lane<'_>,
    how: &[Extrapolation],
    sides: &mut [f64],
    pivots: &mut [f64],
    end: usize,
    slack: f64,
) -> Option<usize> {
    match op.position {
        Position::DrivenAngle(_) => sweep_batch::<RATES, DrivenAngle>(op, lane, how, sides, pivots, end, slack),
        Position::DrivenDistance { .. } => {
            sweep_group::<RATES, DrivenDistanceK>(op, lane, how, sides, pivots, end, slack)
        }
        Position::Rrr(_) => sweep_batch::<RATES, Rrr>(op, lane, how, sides, pivots, end, slack),
        Position::Rrp(_) => sweep_batch::<RATES, Rrp>(op, lane, how, sides, pivots, end, slack),
        Position::Rpr(_) => sweep_batch::<RATES, Rpr>(op, lane, how, sides, pivots, end, slack),
        Position::Prp { .. } => sweep_group::<RATES, PrpK>(op, lane, how, sides, pivots, end, slack),
        Position::Rpp { .. } => sweep_group::<RATES, RppK>(op, lane, how, sides, pivots, end, slack),
        // Not swept (a scene with these is stepped).
        Position::Triad(_) | Position::Newton => Some(0),
    }
}

impl Sweep {
    /// The laws at every step of `times` (each driver's values, and with `rates` the whole
    /// jets), as the steps would evaluate them: the number of steps before the first where a
    /// law is not finite.
    fn laws(&mut self, drivers: &[crate::solve::linkage::Driver], times: &[f64], rates: bool) -> usize {
        let (count, nd) = (times.len(), drivers.len());
        let mut end = count;
        self.values.clear();
        self.jets.clear();
        if rates {
            'steps: for (k, &t) in times.iter().enumerate() {
                for d in drivers {
                    let Some(jet) = d.law.eval(t).finite() else {
                        self.jets.truncate(k * nd);
                        end = k;
                        break 'steps;
                    };
                    self.jets.push(jet);
                }
            }
            self.values.resize(nd * count, 0.0);
            for (k, jets) in self.jets.chunks_exact(nd.max(1)).enumerate().take(end) {
                for (d, jet) in jets.iter().enumerate() {
                    self.values[d * count + k] = jet.0;
                }
            }
        } else {
            for (di, d) in drivers.iter().enumerate() {
                for &t in &times[..end] {
                    let value = match d.law.value(t) {
                        Some(v) if v.is_finite() => Some(v),
                        _ => whole_law(d, t).ok().map(|jet| jet.0),
                    };
                    let Some(value) = value else {
                        end = self.values.len() - di * count;
                        break;
                    };
                    self.values.push(value);
                }
                self.values.resize((di + 1) * count, f64::NAN);
            }
        }
        end
    }

    /// Each of the first `end` steps' prediction (and its ratio or time step, for the
    /// batches), from the solver's state before the sweep: whether its rates belong to its
    /// last step, its last time step and its time `t_last`.
    fn predictions(&mut self, times: &[f64], end: usize, before: (bool, Option<f64>, f64), rates: bool) {
        for v in [&mut self.linear, &mut self.taylor] {
            v.clear();
            v.resize(end, f64::NAN);
        }
        self.how.clear();
        self.how.resize(end, Extrapolation::Hold);
        let (mut rates_valid, mut dt_prev, mut t0) = before;
        let steps = self.how.iter_mut().zip(&mut self.linear).zip(&mut self.taylor);
        for (((how, linear), taylor), &t) in steps.zip(&times[..end]) {
            let dt = t - t0;
            *how = Extrapolation::of(rates_valid, dt_prev, dt);
            match *how {
                Extrapolation::Linear(f) => *linear = f,
                Extrapolation::Taylor(dt) => *taylor = dt,
                Extrapolation::Hold => {}
            }
            (rates_valid, dt_prev, t0) = (rates, Some(dt), t);
        }
    }
}

impl AssurSolver {
    /// Positions (and with `rates`, velocities and accelerations) at `times` by a sweep
    /// (see [`AssurSolver::positions_into`], [`AssurSolver::motion_into`]) from the last
    /// step solved, each step appended to `out`: the number of steps solved, all of them
    /// unless one cannot be (the solver then stands after the step before it).
    pub(super) fn sweep(&mut self, times: &[f64], out: &mut Motion, rates: bool) -> usize {
        let Some(t_last) = self.inner.t else { return 0 };
        let end = self.sweep.laws(&self.inner.mech.drivers, times, rates);
        self.sweep.predictions(times, end, (self.rates_valid, self.dt_prev, t_last), rates);
        if end == 0 {
            return 0;
        }
        self.start_tracks(end, rates);
        // The motion's rows, written by the groups as they sweep (cut back to the steps
        // every group solved).
        let n = 3 * self.inner.poses.len();
        let first = out.q.len();
        out.q.resize(first + end * n, 0.0);
        if rates {
            out.qd.resize(first + end * n, 0.0);
            out.qdd.resize(first + end * n, 0.0);
        }
        let end = self.sweep_groups(times.len(), end, out, first, rates);
        out.q.truncate(first + end * n);
        if rates {
            out.qd.truncate(first + end * n);
            out.qdd.truncate(first + end * n);
        }
        if end == 0 {
            return 0;
        }
        self.settle(times, end, t_last, out, rates);
        end
    }

    /// Room for a sweep of `steps` steps, and each body's entries before them: the step
    /// before the last (its q: what the prediction reads), the last (its cached pose, whose
    /// origin and angle are its q: what a group reads as its bodies' last); the last step's
    /// rates (what Taylor's prediction reads).
    fn start_tracks(&mut self, steps: usize, rates: bool) {
        let sw = &mut self.sweep;
        // Not cleared: a group reads only what this sweep has written (the first two
        // entries of each body, the steps the groups before it solved, its own last
        // steps), so the buffers only grow.
        sw.tracks.reset(self.inner.poses.len(), steps);
        if sw.scratch.len() < SCRATCH * steps {
            sw.scratch.resize(SCRATCH * steps, 0.0);
        }
        for (b, &p) in self.inner.poses.iter().enumerate() {
            let q = &self.q_prev[3 * b..3 * b + 3];
            sw.tracks.set(b, 0, Pose { r: Vector::new(q[0], q[1]), phi: q[2], ..GROUND_POSE });
            sw.tracks.set(b, 1, p);
            sw.tracks.set_rates(b, 1, Rates { qd: coords(&self.inner.qd, b), qdd: coords(&self.inner.qdd, b) });
        }
        let groups = self.ops.len();
        sw.sides.clear();
        sw.sides.resize(groups * steps, 0.0);
        sw.pivots.clear();
        if rates {
            sw.pivots.resize(groups * steps, 1.0);
        }
    }

    /// Every group swept over the `steps` steps (of `count` times) in solving order, its
    /// bodies' rows written into `out` from row `first`: the number of steps every group
    /// solved. Where a group stops short, every group's branch is taken back to the last
    /// step all solved.
    fn sweep_groups(&mut self, count: usize, steps: usize, out: &mut Motion, first: usize, rates: bool) -> usize {
        let sw = &mut self.sweep;
        let (n, nd) = (3 * self.inner.poses.len(), self.inner.laws.len());
        let slack = crate::geom::tol::RESIDUAL_REL * self.inner.mech.length_scale;
        let mut end = steps;
        let mut branches = Vec::with_capacity(self.ops.len());
        for (gi, op) in self.ops.iter_mut().enumerate() {
            branches.push(op.side);
            let lane = Lane {
                tracks: &mut sw.tracks,
                k: 0,
                jets: &sw.jets,
                nd,
                how: Extrapolation::Hold,
                linear: &sw.linear,
                taylor: &sw.taylor,
                values: &sw.values,
                count,
                steps,
                q: &mut out.q[first..],
                qd: if rates { &mut out.qd[first..] } else { &mut [] },
                qdd: if rates { &mut out.qdd[first..] } else { &mut [] },
                n,
                scratch: &mut sw.scratch[..SCRATCH * steps],
            };
            let (how, sides) = (&sw.how[..], &mut sw.sides[gi * steps..(gi + 1) * steps]);
            let stop = if rates {
                sweep_kind::<true>(op, lane, how, sides, &mut sw.pivots[gi * steps..(gi + 1) * steps], end, slack)
            } else {
                sweep_kind::<false>(op, lane, how, sides, &mut [], end, slack)
            };
            if let Some(k) = stop {
                end = end.min(k);
            }
        }
        if end < steps {
            // Every group's branch after the last step solved (a group swept further than a
            // later group could follow is taken back).
            for (gi, op) in self.ops.iter_mut().enumerate() {
                op.side = if end == 0 { branches[gi] } else { sw.sides[gi * steps + end - 1] };
            }
        }
        end
    }

    /// The solver after the first `end` steps of `times` were swept (`end` ≥ 1), as stepping
    /// would leave it: q and the poses of the last step, the step before it for the next
    /// prediction, the time, the laws, the rates and their state (`t_last` the time before
    /// the sweep).
    fn settle(&mut self, times: &[f64], end: usize, t_last: f64, out: &mut Motion, rates: bool) {
        let n = 3 * self.inner.poses.len();
        if end >= 2 {
            let before = out.q.len() - 2 * n;
            self.q_prev.copy_from_slice(&out.q[before..before + n]);
        } else {
            self.q_prev.copy_from_slice(&self.inner.q);
        }
        self.inner.q.copy_from_slice(&out.q[out.q.len() - n..]);
        for (b, p) in self.inner.poses.iter_mut().enumerate() {
            *p = self.sweep.tracks.pose(b, end + 1);
        }
        let t = times[end - 1];
        if rates {
            self.settle_rates(times, end, out);
            // Sets the laws and their rates as the step did; it succeeded there.
            let _ = self.inner.eval_laws(t);
        } else {
            if self.rates_valid {
                // A positions-only step keeps the rates it predicted from.
                self.qd_prev.copy_from_slice(&self.inner.qd);
                self.qdd_prev.copy_from_slice(&self.inner.qdd);
            }
            // Sets the laws' values (and any whole jet) as the step did; it succeeded there.
            let _ = self.inner.eval_law_values(t);
        }
        self.dt_prev = Some(t - if end >= 2 { times[end - 2] } else { t_last });
        self.how = self.sweep.how[end - 1];
        self.rates_valid = rates;
        self.fallback = None;
        self.inner.t = Some(t);
    }

    /// The rates after a sweep with rates of `end` steps (of `times`, each a row of `out`):
    /// those of the step before the last (what stepping leaves swapped out) and of the last,
    /// each step's near-singular report, each group's conditioning at the last step.
    fn settle_rates(&mut self, times: &[f64], end: usize, out: &mut Motion) {
        let (nb, n) = (self.inner.poses.len(), 3 * self.inner.poses.len());
        let sw = &self.sweep;
        let before = if end >= 2 { end } else { 1 };
        for b in 0..nb {
            let r = sw.tracks.rates(b, before);
            self.qd_prev[3 * b..3 * b + 3].copy_from_slice(&r.qd);
            self.qdd_prev[3 * b..3 * b + 3].copy_from_slice(&r.qdd);
        }
        self.inner.qd.copy_from_slice(&out.qd[out.qd.len() - n..]);
        self.inner.qdd.copy_from_slice(&out.qdd[out.qdd.len() - n..]);
        self.report_near_singular(&times[..end], out);
        let steps = self.sweep.sides.len() / self.ops.len().max(1);
        for (gi, plan) in self.plans.iter_mut().enumerate() {
            plan.pivot = self.sweep.pivots[gi * steps + end - 1];
        }
    }

    /// Each swept step's near-singular report (at `solved`, the steps every group solved):
    /// the group whose rates are the worst conditioned, as a step finds it; the last step's
    /// also the solver's, as a step leaves it.
    fn report_near_singular(&mut self, solved: &[f64], out: &mut Motion) {
        let first_step = out.iterations.len();
        out.iterations.extend(std::iter::repeat_n(0, solved.len()));
        self.inner.near = None;
        let groups = self.ops.len();
        let steps = self.sweep.sides.len() / groups.max(1);
        for (k, &tk) in solved.iter().enumerate() {
            let mut worst: Option<(f64, usize)> = None;
            for gi in 0..groups {
                let rho = self.sweep.pivots[gi * steps + k];
                if worst.is_none_or(|(p, _)| rho < p) {
                    worst = Some((rho, gi));
                }
            }
            if let Some((pivot, gi)) = worst.filter(|&(pivot, _)| pivot < NEAR_SINGULAR_PIVOT_REL) {
                let _ = self.inner.eval_law_values(tk);
                let near = NearSingular {
                    t: tk,
                    pivot,
                    drivers: self.inner.driver_values(),
                    constraints: self.plans[gi].constraint_names(&self.inner),
                };
                if k + 1 == solved.len() {
                    self.inner.near = Some(near.clone());
                }
                out.near.push((first_step + k, near));
            }
        }
    }
}
