//! Bounded lists: the one way every list of this crate is kept small however long the program.
//! When a list is full, every other item goes ([`thin`]) and what comes next is kept as sparsely.

/// Drops every other item (the second, the fourth, …) but those `keep(items, index)` marks:
/// the thinning of every bounded list here (the viewer's frames, path and lines, the tool's
/// strokes, the pictures' path and curves).
pub(crate) fn thin<T>(items: &mut Vec<T>, keep: impl Fn(&[T], usize) -> bool) {
    let marks: Vec<bool> = (0..items.len()).map(|i| i % 2 == 0 || keep(items, i)).collect();
    let mut index = 0;
    items.retain(|_| {
        index += 1;
        marks[index - 1]
    });
}

/// Keeps every `stride`-th item pushed; when full, drops every other kept item and doubles the
/// stride, so memory stays bounded however many items arrive. The last item is kept aside.
#[derive(Debug, Clone)]
pub(crate) struct Decimator<T> {
    pub(crate) kept: Vec<T>,
    last: Option<T>,
    pub(crate) stride: usize,
    pub(crate) seen: usize,
    capacity: usize,
}

impl<T: Clone> Decimator<T> {
    pub(crate) fn new(capacity: usize) -> Self {
        Decimator { kept: Vec::new(), last: None, stride: 1, seen: 0, capacity: capacity.max(2) }
    }

    pub(crate) fn push(&mut self, item: T) {
        if self.seen.is_multiple_of(self.stride) {
            if self.kept.len() >= self.capacity {
                thin(&mut self.kept, |_, _| false);
                self.stride *= 2;
            }
            if self.seen.is_multiple_of(self.stride) {
                self.kept.push(item.clone());
            }
        }
        self.last = Some(item);
        self.seen += 1;
    }

    /// The kept items and the last one (when it was not kept already).
    pub(crate) fn items(&self) -> impl Iterator<Item = &T> {
        let last_kept = self.seen > 0 && (self.seen - 1).is_multiple_of(self.stride);
        self.kept.iter().chain(self.last.iter().filter(move |_| !last_kept))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thinning_keeps_every_other_item_and_those_marked() {
        let mut items: Vec<u32> = (0..7).collect();
        thin(&mut items, |_, _| false);
        assert_eq!(items, [0, 2, 4, 6]);
        let mut items: Vec<u32> = (0..8).collect();
        thin(&mut items, |items, i| items[i] == 5 || i + 1 == items.len());
        assert_eq!(items, [0, 2, 4, 5, 6, 7]);
    }

    #[test]
    fn decimation_keeps_a_bounded_uniform_subset_and_the_last_item() {
        let mut decimator = Decimator::new(8);
        for item in 0..100 {
            decimator.push(item);
        }
        let items: Vec<i32> = decimator.items().copied().collect();
        assert!(items.len() <= 9, "{items:?}");
        assert_eq!(items[0], 0);
        assert_eq!(*items.last().unwrap(), 99);
        let step = items[1] - items[0];
        assert!(items[..items.len() - 1].windows(2).all(|w| w[1] - w[0] == step), "{items:?}");
    }
}
