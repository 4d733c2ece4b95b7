//! Sorters: the event-driven engine's priority queue of future events (DynamO's name for
//! it). Each particle has one entry, its earliest predicted event; the sorter hands out the
//! particle with the earliest entry. Two implementations give the same events in the same
//! order: an indexed heap ([`heap`], O(log N) per update) and a calendar queue of buckets
//! ([`buckets`], O(1) per update). Measured against each other in docs/event-driven.md.

pub mod buckets;
pub mod heap;

pub use buckets::BucketSorter;
pub use heap::HeapSorter;

use serde::{Deserialize, Serialize};

/// Which sorter the event-driven engine uses.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SorterKind {
    /// Indexed 8-ary heap: O(log N) per update.
    #[default]
    Heap,
    /// Calendar queue (Paul 2007): O(1) per update.
    Buckets,
}

/// The sorter in use.
#[derive(Debug, Clone)]
pub(crate) enum Sorter {
    Heap(HeapSorter),
    Buckets(BucketSorter),
}

impl Sorter {
    pub(crate) fn new(kind: SorterKind, n: usize) -> Self {
        match kind {
            SorterKind::Heap => Sorter::Heap(HeapSorter::new(n)),
            SorterKind::Buckets => Sorter::Buckets(BucketSorter::new(n)),
        }
    }

    pub(crate) fn kind(&self) -> SorterKind {
        match self {
            Sorter::Heap(_) => SorterKind::Heap,
            Sorter::Buckets(_) => SorterKind::Buckets,
        }
    }

    /// The particle with the earliest event and its time.
    #[inline]
    pub(crate) fn peek(&mut self) -> Option<(usize, f64)> {
        match self {
            Sorter::Heap(q) => q.peek(),
            Sorter::Buckets(q) => q.peek(),
        }
    }

    #[inline]
    pub(crate) fn update(&mut self, i: usize, t: f64) {
        match self {
            Sorter::Heap(q) => q.update(i, t),
            Sorter::Buckets(q) => q.update(i, t),
        }
    }

    /// The particle probably next after the earliest (for prefetching), if known.
    #[inline]
    pub(crate) fn runner_up(&self) -> Option<usize> {
        match self {
            Sorter::Heap(q) => q.runner_up(),
            Sorter::Buckets(_) => None,
        }
    }

    pub(crate) fn time_of(&self, i: usize) -> f64 {
        match self {
            Sorter::Heap(q) => q.time_of(i),
            Sorter::Buckets(q) => q.time_of(i),
        }
    }

    pub(crate) fn memory_bytes(&self) -> usize {
        match self {
            Sorter::Heap(q) => q.memory_bytes(),
            Sorter::Buckets(q) => q.memory_bytes(),
        }
    }
}
