//! The event calendar: an indexed binary min-heap with one entry per particle (its earliest
//! predicted event), as in Marín, Risso & Cordero, J. Comput. Phys. 109, 306 (1993).
//! Memory is O(N) whatever the number of predictions; an update moves one entry.

/// Min-heap of (time, particle) with O(log N) update of any particle's time.
#[derive(Debug, Clone)]
pub struct EventQueue {
    heap: Vec<u32>,
    slot: Vec<u32>,
    time: Vec<f64>,
}

impl EventQueue {
    /// All `n` particles at time +infinity.
    pub fn new(n: usize) -> Self {
        EventQueue {
            heap: (0..n as u32).collect(),
            slot: (0..n as u32).collect(),
            time: vec![f64::INFINITY; n],
        }
    }

    /// The particle with the earliest event and its time.
    #[inline]
    pub fn peek(&self) -> Option<(usize, f64)> {
        self.heap
            .first()
            .map(|&i| (i as usize, self.time[i as usize]))
    }

    /// Bytes held by the heap.
    pub fn memory_bytes(&self) -> usize {
        (self.heap.capacity() + self.slot.capacity()) * 4 + self.time.capacity() * 8
    }

    pub fn time_of(&self, i: usize) -> f64 {
        self.time[i]
    }

    /// Sets the event time of particle i.
    pub fn update(&mut self, i: usize, t: f64) {
        let old = self.time[i];
        self.time[i] = t;
        let s = self.slot[i] as usize;
        if t < old {
            self.sift_up(s);
        } else {
            self.sift_down(s);
        }
    }

    fn key(&self, s: usize) -> f64 {
        self.time[self.heap[s] as usize]
    }

    fn swap(&mut self, a: usize, b: usize) {
        self.heap.swap(a, b);
        self.slot[self.heap[a] as usize] = a as u32;
        self.slot[self.heap[b] as usize] = b as u32;
    }

    fn sift_up(&mut self, mut s: usize) {
        while s > 0 {
            let parent = (s - 1) / 2;
            if self.key(s) >= self.key(parent) {
                break;
            }
            self.swap(s, parent);
            s = parent;
        }
    }

    fn sift_down(&mut self, mut s: usize) {
        let n = self.heap.len();
        loop {
            let (l, r) = (2 * s + 1, 2 * s + 2);
            let mut smallest = s;
            if l < n && self.key(l) < self.key(smallest) {
                smallest = l;
            }
            if r < n && self.key(r) < self.key(smallest) {
                smallest = r;
            }
            if smallest == s {
                break;
            }
            self.swap(s, smallest);
            s = smallest;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orders_random_updates() {
        let mut q = EventQueue::new(100);
        let mut x = 12345u64;
        let mut times = vec![f64::INFINITY; 100];
        for _ in 0..2000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let i = (x >> 33) as usize % 100;
            let t = (x >> 11) as f64 / (1u64 << 53) as f64;
            q.update(i, t);
            times[i] = t;
            let min = times.iter().cloned().fold(f64::INFINITY, f64::min);
            assert_eq!(q.peek().unwrap().1, min);
        }
    }
}
