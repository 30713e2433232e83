//! Data parallelism where there are threads. With the feature `parallel` (the command line
//! has it) this is rayon: [`join`] and the parallel iterators of `prelude`. Without it (the
//! browser's module, which has one thread and would carry ~120 KB of rayon's pool for
//! nothing) the same calls run in order on the calling thread: `par_iter`, `into_par_iter`,
//! `par_chunks` and `par_chunks_mut` give a `Seq`, an iterator with rayon's two-closure
//! `fold` and `reduce` and a `with_min_len` that does nothing.
//!
//! Results do not depend on the thread count either way: what draws random numbers draws
//! stream k in chunk k (solve::chain::stackup, solve::tolerance::monte_carlo), and what sums
//! in parallel merges in a fixed order, so one thread gives the bits many threads give.

#[cfg(feature = "parallel")]
pub use rayon::join;

/// The parallel iterators' traits: rayon's, or their sequential stand-ins.
#[cfg(feature = "parallel")]
pub mod prelude {
    pub use rayon::prelude::*;
}

#[cfg(not(feature = "parallel"))]
pub use sequential::{join, prelude};

#[cfg(not(feature = "parallel"))]
mod sequential {
    /// Runs `a`, then `b` (rayon's `join` on one thread).
    pub fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
    where
        A: FnOnce() -> RA,
        B: FnOnce() -> RB,
    {
        let ra = a();
        (ra, b())
    }

    /// A "parallel" iterator run in order: a std iterator with rayon's adapters whose
    /// meaning differs from std's (`fold` and `reduce` take an identity closure) as inherent
    /// methods, and the adapters that keep it a [`Seq`] (`map`, `enumerate`, `zip`).
    pub struct Seq<I>(I);

    impl<I: Iterator> Iterator for Seq<I> {
        type Item = I::Item;

        fn next(&mut self) -> Option<I::Item> {
            self.0.next()
        }

        fn size_hint(&self) -> (usize, Option<usize>) {
            self.0.size_hint()
        }
    }

    impl<I: Iterator> Seq<I> {
        /// Each item through `f` (std's `map`, kept a [`Seq`]).
        pub fn map<B, F: FnMut(I::Item) -> B>(self, f: F) -> Seq<std::iter::Map<I, F>> {
            Seq(self.0.map(f))
        }

        /// Each item with its index (std's `enumerate`, kept a [`Seq`]).
        pub fn enumerate(self) -> Seq<std::iter::Enumerate<I>> {
            Seq(self.0.enumerate())
        }

        /// Pairs with `other`'s items (std's `zip`, kept a [`Seq`]).
        pub fn zip<J: IntoIterator>(self, other: J) -> Seq<std::iter::Zip<I, J::IntoIter>> {
            Seq(self.0.zip(other))
        }

        /// rayon's smallest piece of work per thread: nothing to split here.
        pub fn with_min_len(self, _min: usize) -> Self {
            self
        }

        /// rayon's `fold`: every item folded into one accumulator started from `identity()`
        /// (rayon makes one per piece of work, here there is one), yielded as the only item.
        pub fn fold<T, ID, F>(self, identity: ID, op: F) -> Seq<std::iter::Once<T>>
        where
            ID: Fn() -> T,
            F: FnMut(T, I::Item) -> T,
        {
            Seq(std::iter::once(self.0.fold(identity(), op)))
        }

        /// rayon's `reduce`: the items combined by `op`, `identity()` when there are none.
        pub fn reduce<ID, F>(self, identity: ID, op: F) -> I::Item
        where
            ID: Fn() -> I::Item,
            F: FnMut(I::Item, I::Item) -> I::Item,
        {
            self.0.fold(identity(), op)
        }
    }

    /// rayon's iterator traits, each making a [`Seq`].
    pub mod prelude {
        use super::Seq;

        /// `into_par_iter`: the items, by value.
        pub trait IntoParallelIterator: IntoIterator + Sized {
            /// The items in order.
            fn into_par_iter(self) -> Seq<Self::IntoIter> {
                Seq(self.into_iter())
            }
        }

        impl<T: IntoIterator> IntoParallelIterator for T {}

        /// `par_iter`: the items, by reference.
        pub trait IntoParallelRefIterator<'a> {
            /// The iterator over references.
            type Iter: Iterator;
            /// The items in order.
            fn par_iter(&'a self) -> Seq<Self::Iter>;
        }

        impl<'a, T: ?Sized + 'a> IntoParallelRefIterator<'a> for T
        where
            &'a T: IntoIterator,
        {
            type Iter = <&'a T as IntoIterator>::IntoIter;

            fn par_iter(&'a self) -> Seq<Self::Iter> {
                Seq(self.into_iter())
            }
        }

        /// `par_chunks` on a slice.
        pub trait ParallelSlice<T> {
            /// Chunks of `size` items, the last one shorter.
            fn par_chunks(&self, size: usize) -> Seq<std::slice::Chunks<'_, T>>;
        }

        impl<T> ParallelSlice<T> for [T] {
            fn par_chunks(&self, size: usize) -> Seq<std::slice::Chunks<'_, T>> {
                Seq(self.chunks(size))
            }
        }

        /// `par_chunks_mut` on a slice.
        pub trait ParallelSliceMut<T> {
            /// Mutable chunks of `size` items, the last one shorter.
            fn par_chunks_mut(&mut self, size: usize) -> Seq<std::slice::ChunksMut<'_, T>>;
        }

        impl<T> ParallelSliceMut<T> for [T] {
            fn par_chunks_mut(&mut self, size: usize) -> Seq<std::slice::ChunksMut<'_, T>> {
                Seq(self.chunks_mut(size))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::prelude::*;

    /// The calls the library makes mean the same with and without threads (`cargo test --lib
    /// --no-default-features par::` runs the sequential side).
    #[test]
    fn fold_and_reduce_follow_rayons_meaning() {
        let mut v: Vec<u32> = (1..=10).collect();
        v.par_chunks_mut(4).enumerate().for_each(|(k, c)| c.iter_mut().for_each(|x| *x += k as u32));
        assert_eq!(v, [1, 2, 3, 4, 6, 7, 8, 9, 11, 12]);
        let sums: Vec<u32> = v.par_chunks(3).with_min_len(2).fold(|| 0, |a, c| a + c.iter().sum::<u32>()).collect();
        assert_eq!(sums.iter().sum::<u32>(), 63);
        let total = v.par_iter().zip(&v).map(|(x, y)| x * y).reduce(|| 0, |a, b| a + b);
        assert_eq!(total, v.iter().map(|x| x * x).sum::<u32>());
        let none: Vec<u32> = Vec::new();
        assert_eq!(none.into_par_iter().map(|x| x + 1).reduce(|| 0, |a, b| a + b), 0);
        let (a, b) = super::join(|| 1, || 2);
        assert_eq!((a, b), (1, 2));
    }
}
