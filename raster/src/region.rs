//! Pixel rectangles and their unions, walked as disjoint row spans.
//!
//! The region an evaluation must re-render is the union of a few rectangles (the
//! moving shapes' pixel bounds, plus those of any static shape drawn above them that
//! they touch). Rather than their bounding box, which for shapes far apart is most of
//! the image, the union is decomposed row by row into disjoint spans, so every pixel is
//! copied, drawn and scored once.

/// A non-empty half-open rectangle of pixels [x0, x1) × [y0, y1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PixelRect {
    pub(crate) x0: u32,
    pub(crate) y0: u32,
    pub(crate) x1: u32,
    pub(crate) y1: u32,
}

impl PixelRect {
    /// The rectangle, or `None` if it is empty.
    pub(crate) fn new(x0: u32, y0: u32, x1: u32, y1: u32) -> Option<Self> {
        (x0 < x1 && y0 < y1).then_some(PixelRect { x0, y0, x1, y1 })
    }

    pub(crate) fn intersects(&self, other: &PixelRect) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }
}

/// Pixels [x0, x1) of row y.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Span {
    pub(crate) y: u32,
    pub(crate) x0: u32,
    pub(crate) x1: u32,
}

/// A union of rectangles with its disjoint row spans. Buffers are kept between uses,
/// so after the first few evaluations building a region allocates nothing.
#[derive(Debug, Default)]
pub(crate) struct Region {
    rects: Vec<PixelRect>,
    spans: Vec<Span>,
    row: Vec<(u32, u32)>,
}

impl Region {
    pub(crate) fn clear(&mut self) {
        self.rects.clear();
        self.spans.clear();
    }

    pub(crate) fn push(&mut self, rect: PixelRect) {
        self.rects.push(rect);
    }

    pub(crate) fn intersects(&self, rect: &PixelRect) -> bool {
        self.rects.iter().any(|r| r.intersects(rect))
    }

    /// Decomposes the union into disjoint spans, sorted by row then x.
    pub(crate) fn build_spans(&mut self) {
        self.spans.clear();
        let (Some(top), Some(bottom)) = (
            self.rects.iter().map(|r| r.y0).min(),
            self.rects.iter().map(|r| r.y1).max(),
        ) else {
            return;
        };
        for y in top..bottom {
            self.row.clear();
            self.row.extend(
                self.rects
                    .iter()
                    .filter(|r| r.y0 <= y && y < r.y1)
                    .map(|r| (r.x0, r.x1)),
            );
            self.row.sort_unstable();
            let mut current: Option<(u32, u32)> = None;
            for &(a, b) in &self.row {
                current = match current {
                    Some((c0, c1)) if a <= c1 => Some((c0, c1.max(b))),
                    Some((c0, c1)) => {
                        self.spans.push(Span { y, x0: c0, x1: c1 });
                        Some((a, b))
                    }
                    None => Some((a, b)),
                };
            }
            if let Some((x0, x1)) = current {
                self.spans.push(Span { y, x0, x1 });
            }
        }
    }

    pub(crate) fn spans(&self) -> &[Span] {
        &self.spans
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_rects_give_disjoint_spans_covering_the_union() {
        let mut region = Region::default();
        region.push(PixelRect::new(0, 0, 4, 2).unwrap());
        region.push(PixelRect::new(2, 1, 6, 3).unwrap());
        region.push(PixelRect::new(8, 1, 9, 2).unwrap());
        region.build_spans();
        let spans: Vec<_> = region.spans().iter().map(|s| (s.y, s.x0, s.x1)).collect();
        assert_eq!(spans, vec![(0, 0, 4), (1, 0, 6), (1, 8, 9), (2, 2, 6)]);
    }

    #[test]
    fn empty_rects_are_rejected() {
        assert!(PixelRect::new(3, 0, 3, 5).is_none());
        assert!(PixelRect::new(0, 5, 3, 5).is_none());
    }
}
