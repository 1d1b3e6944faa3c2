//! A fixed-capacity ring buffer: the last K accepted samples, for drawing the posterior cloud
//! (the dissertation's figures overlay 1000 samples as thin lines).

/// Keeps the most recent `capacity` items.
#[derive(Debug, Clone)]
pub struct Ring<T> {
    items: Vec<T>,
    next: usize,
    capacity: usize,
}

impl<T> Ring<T> {
    /// An empty ring holding at most `capacity` items (0 keeps nothing).
    pub fn new(capacity: usize) -> Self {
        Ring { items: Vec::new(), next: 0, capacity }
    }

    /// Adds an item, evicting the oldest when full.
    pub fn push(&mut self, item: T) {
        if self.capacity == 0 {
            return;
        }
        if self.items.len() < self.capacity {
            self.items.push(item);
        } else {
            self.items[self.next] = item;
        }
        self.next = (self.next + 1) % self.capacity;
    }

    /// Number of items held.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Whether the ring is empty.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Items from oldest to newest.
    pub fn iter(&self) -> impl Iterator<Item = &T> {
        let split = if self.items.len() < self.capacity { 0 } else { self.next };
        self.items[split..].iter().chain(self.items[..split].iter())
    }

    /// Removes everything.
    pub fn clear(&mut self) {
        self.items.clear();
        self.next = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::Ring;

    #[test]
    fn keeps_the_newest_in_order() {
        let mut r = Ring::new(3);
        for i in 0..5 {
            r.push(i);
        }
        assert_eq!(r.iter().copied().collect::<Vec<_>>(), vec![2, 3, 4]);
        let mut r = Ring::new(3);
        r.push(1);
        r.push(2);
        assert_eq!(r.iter().copied().collect::<Vec<_>>(), vec![1, 2]);
        let mut z = Ring::new(0);
        z.push(1);
        assert!(z.is_empty());
    }
}
