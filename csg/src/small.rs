//! A short list stored inline up to `N` items, on the heap beyond: the triangles and corners of
//! a face piece (most have one or two triangles and two or three corners), so splitting a face
//! does not allocate.

/// A short list stored inline up to `N` items (most face pieces have one or two triangles and
/// two or three corners: no allocation for them), on the heap beyond.
#[derive(Clone, Debug)]
pub(crate) enum Small<T: Copy, const N: usize> {
    /// The first `len` items of the array.
    Inline([Option<T>; N], u8),
    Heap(Vec<T>),
}

/// The iterator of [`Small`].
pub(crate) type SmallIter<'a, T> =
    std::iter::Chain<std::iter::Flatten<std::slice::Iter<'a, Option<T>>>, std::slice::Iter<'a, T>>;

impl<T: Copy, const N: usize> Default for Small<T, N> {
    fn default() -> Self {
        Small::Inline([None; N], 0)
    }
}

impl<T: Copy, const N: usize> Small<T, N> {
    pub fn push(&mut self, x: T) {
        match self {
            Small::Inline(items, len) if (*len as usize) < N => {
                items[*len as usize] = Some(x);
                *len += 1;
            }
            Small::Inline(items, _) => {
                let mut v: Vec<T> = items.iter().flatten().copied().collect();
                v.push(x);
                *self = Small::Heap(v);
            }
            Small::Heap(v) => v.push(x),
        }
    }

    pub fn len(&self) -> usize {
        match self {
            Small::Inline(_, len) => *len as usize,
            Small::Heap(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn iter(&self) -> SmallIter<'_, T> {
        let (inline, heap): (&[Option<T>], &[T]) = match self {
            Small::Inline(items, len) => (&items[..*len as usize], &[]),
            Small::Heap(v) => (&[], v),
        };
        inline.iter().flatten().chain(heap)
    }
}

impl<T: Copy, const N: usize> std::ops::Index<usize> for Small<T, N> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        match self {
            Small::Inline(items, len) => {
                assert!(i < *len as usize, "index {i} out of range");
                items[i].as_ref().expect("set below len")
            }
            Small::Heap(v) => &v[i],
        }
    }
}

impl<T: Copy + PartialEq, const N: usize> PartialEq for Small<T, N> {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len() && self.iter().eq(other.iter())
    }
}

impl<T: Copy + Eq, const N: usize> Eq for Small<T, N> {}

impl<T: Copy, const N: usize> FromIterator<T> for Small<T, N> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Self {
        let mut s = Small::default();
        for x in iter {
            s.push(x);
        }
        s
    }
}

impl<'a, T: Copy, const N: usize> IntoIterator for &'a Small<T, N> {
    type Item = &'a T;
    type IntoIter = SmallIter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}
