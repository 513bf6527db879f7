//! A bounding volume hierarchy built with the binned surface-area heuristic.
//!
//! The hierarchy knows only primitive boxes; the caller intersects the primitives of a
//! leaf (triangles of a mesh, or whole objects of a scene) through a closure.
//!
//! **Build.** Top-down. For a node with primitives P and bounds B, the centroids are
//! binned into [`BINS`] equal slots along each axis, and each of the `BINS − 1` planes
//! between slots is scored with the SAH cost
//!
//! C(split) = C_trav + (A(L)·|L| + A(R)·|R|) / A(B) · C_isect,
//!
//! A the surface area. The node becomes a leaf when no split beats the leaf cost |P|·C_isect
//! and |P| ≤ [`MAX_LEAF`], or when all centroids coincide. Buffers are kept between
//! builds, so rebuilding a mesh of unchanged size (the CAUSTIC height field, whose
//! vertices θ moves) allocates nothing.
//!
//! **Traversal.** Depth-first with a fixed stack of [`STACK_DEPTH`] entries (the build
//! stops splitting at that depth), visiting the nearer child first and skipping nodes
//! whose entry distance exceeds the closest hit so far.

use super::math::{Aabb, Vec3};

/// Centroid bins per axis.
pub const BINS: usize = 16;
/// Leaves never hold more than this many primitives, unless their centroids coincide
/// or the tree is [`STACK_DEPTH`] deep.
pub const MAX_LEAF: usize = 4;
/// Maximum tree depth, which is also the traversal stack size.
pub const STACK_DEPTH: usize = 64;
/// SAH cost of visiting a node relative to intersecting one primitive (C_trav/C_isect).
const TRAVERSAL_COST: f32 = 0.5;

#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: first entry in `order`; interior: index of the left child (right = +1).
    first: u32,
    /// Primitive count; 0 for interior nodes.
    count: u32,
}

/// A flattened BVH over primitives given by their bounding boxes.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Primitive indices, grouped by leaf.
    order: Vec<u32>,
    /// Build scratch: primitive centroids.
    centroids: Vec<Vec3>,
    /// Build scratch: pending (node, first, end, depth) ranges.
    pending: Vec<(u32, u32, u32, u32)>,
}

impl Bvh {
    /// An empty hierarchy (no primitive is ever hit).
    pub fn new() -> Bvh {
        Bvh::default()
    }

    /// Rebuilds over the primitives whose boxes are `bounds` (index = primitive id).
    /// Reuses the buffers of the previous build.
    pub fn build(&mut self, bounds: &[Aabb]) {
        self.nodes.clear();
        self.order.clear();
        self.centroids.clear();
        self.pending.clear();
        if bounds.is_empty() {
            return;
        }
        self.order.extend(0..bounds.len() as u32);
        self.centroids.extend(bounds.iter().map(Aabb::centroid));
        self.nodes.push(Node {
            bounds: Aabb::EMPTY,
            first: 0,
            count: 0,
        });
        self.pending.push((0, 0, bounds.len() as u32, 1));
        while let Some((node, first, end, depth)) = self.pending.pop() {
            self.split(bounds, node, first, end, depth);
        }
    }

    fn split(&mut self, bounds: &[Aabb], node: u32, first: u32, end: u32, depth: u32) {
        let range = first as usize..end as usize;
        let mut node_box = Aabb::EMPTY;
        let mut centroid_box = Aabb::EMPTY;
        for &p in &self.order[range.clone()] {
            node_box = node_box.union(bounds[p as usize]);
            centroid_box = centroid_box.include(self.centroids[p as usize]);
        }
        let count = end - first;
        let make_leaf = |nodes: &mut Vec<Node>| {
            nodes[node as usize] = Node {
                bounds: node_box,
                first,
                count,
            };
        };
        let extent = centroid_box.max - centroid_box.min;
        if count == 1 || depth as usize >= STACK_DEPTH || extent.max_component() <= 0.0 {
            make_leaf(&mut self.nodes);
            return;
        }

        // Score every bin boundary on every axis.
        let mut best = (f32::INFINITY, 0usize, 0usize);
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f32 / extent[axis];
            let mut bin_box = [Aabb::EMPTY; BINS];
            let mut bin_count = [0u32; BINS];
            for &p in &self.order[range.clone()] {
                let b = bin_of(
                    self.centroids[p as usize][axis],
                    centroid_box.min[axis],
                    scale,
                );
                bin_box[b] = bin_box[b].union(bounds[p as usize]);
                bin_count[b] += 1;
            }
            // Sweep from the right to get the right-hand areas, then from the left.
            let mut right_area = [0.0f32; BINS];
            let mut acc = Aabb::EMPTY;
            let mut acc_count = 0u32;
            for b in (1..BINS).rev() {
                acc = acc.union(bin_box[b]);
                acc_count += bin_count[b];
                right_area[b] = acc.surface_area() * acc_count as f32;
            }
            let mut left = Aabb::EMPTY;
            let mut left_count = 0u32;
            for b in 0..BINS - 1 {
                left = left.union(bin_box[b]);
                left_count += bin_count[b];
                if left_count == 0 || left_count == count {
                    continue;
                }
                let cost = left.surface_area() * left_count as f32 + right_area[b + 1];
                if cost < best.0 {
                    best = (cost, axis, b);
                }
            }
        }
        let parent_area = node_box.surface_area().max(f32::MIN_POSITIVE);
        let split_cost = TRAVERSAL_COST + best.0 / parent_area;
        if !best.0.is_finite() || (split_cost >= count as f32 && count as usize <= MAX_LEAF) {
            make_leaf(&mut self.nodes);
            return;
        }

        // Partition the range in place around the chosen plane.
        let (_, axis, split_bin) = best;
        let scale = BINS as f32 / extent[axis];
        let (mut lo, mut hi) = (first as usize, end as usize);
        while lo < hi {
            let c = self.centroids[self.order[lo] as usize][axis];
            if bin_of(c, centroid_box.min[axis], scale) <= split_bin {
                lo += 1;
            } else {
                hi -= 1;
                self.order.swap(lo, hi);
            }
        }
        let mid = lo as u32;
        let left = self.nodes.len() as u32;
        let placeholder = Node {
            bounds: Aabb::EMPTY,
            first: 0,
            count: 0,
        };
        self.nodes.push(placeholder);
        self.nodes.push(placeholder);
        self.nodes[node as usize] = Node {
            bounds: node_box,
            first: left,
            count: 0,
        };
        self.pending.push((left, first, mid, depth + 1));
        self.pending.push((left + 1, mid, end, depth + 1));
    }

    /// Bounds of everything in the hierarchy ([`Aabb::EMPTY`] when empty).
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// Node count (for tests and statistics).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Closest-hit traversal of the ray `origin + t·dir`, t ∈ (0, `t_max`).
    ///
    /// `hit(prim, t_max)` must return the distance of a hit on primitive `prim` closer
    /// than `t_max`, or `None`. Returns the closest hit distance found.
    #[inline]
    pub fn closest<F: FnMut(u32, f32) -> Option<f32>>(
        &self,
        origin: Vec3,
        dir: Vec3,
        mut t_max: f32,
        mut hit: F,
    ) -> Option<f32> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv_dir = dir.recip();
        let mut found = None;
        let mut stack = [0u32; STACK_DEPTH + 1];
        let mut top = 0usize;
        self.nodes[0].bounds.hit(origin, inv_dir, t_max)?;
        let mut current = 0u32;
        loop {
            let node = &self.nodes[current as usize];
            if node.count > 0 {
                for k in node.first..node.first + node.count {
                    if let Some(t) = hit(self.order[k as usize], t_max) {
                        t_max = t;
                        found = Some(t);
                    }
                }
            } else {
                let (l, r) = (node.first, node.first + 1);
                let tl = self.nodes[l as usize].bounds.hit(origin, inv_dir, t_max);
                let tr = self.nodes[r as usize].bounds.hit(origin, inv_dir, t_max);
                match (tl, tr) {
                    (Some(a), Some(b)) => {
                        let (near, far) = if a <= b { (l, r) } else { (r, l) };
                        stack[top] = far;
                        top += 1;
                        current = near;
                        continue;
                    }
                    (Some(_), None) => {
                        current = l;
                        continue;
                    }
                    (None, Some(_)) => {
                        current = r;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next node that can still hold a closer hit.
            loop {
                if top == 0 {
                    return found;
                }
                top -= 1;
                let candidate = stack[top];
                if self.nodes[candidate as usize]
                    .bounds
                    .hit(origin, inv_dir, t_max)
                    .is_some()
                {
                    current = candidate;
                    break;
                }
            }
        }
    }

    /// Any-hit traversal: true as soon as `hit(prim)` reports a hit in (0, `t_max`).
    #[inline]
    pub fn any<F: FnMut(u32) -> bool>(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut hit: F,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inv_dir = dir.recip();
        let mut stack = [0u32; STACK_DEPTH + 1];
        stack[0] = 0;
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if node.bounds.hit(origin, inv_dir, t_max).is_none() {
                continue;
            }
            if node.count > 0 {
                for k in node.first..node.first + node.count {
                    if hit(self.order[k as usize]) {
                        return true;
                    }
                }
            } else {
                stack[top] = node.first;
                stack[top + 1] = node.first + 1;
                top += 2;
            }
        }
        false
    }
}

#[inline]
fn bin_of(c: f32, min: f32, scale: f32) -> usize {
    (((c - min) * scale) as usize).min(BINS - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box(c: Vec3) -> Aabb {
        Aabb {
            min: c - Vec3::splat(0.1),
            max: c + Vec3::splat(0.1),
        }
    }

    /// Closest hit over a line of boxes matches brute force, and every primitive sits in
    /// exactly one leaf.
    #[test]
    fn closest_hit_matches_brute_force() {
        let boxes: Vec<Aabb> = (0..100)
            .map(|i| {
                let f = i as f32;
                unit_box(Vec3::new(
                    (f * 0.37).sin() * 3.0,
                    (f * 0.91).cos() * 3.0,
                    f * 0.05,
                ))
            })
            .collect();
        let mut bvh = Bvh::new();
        bvh.build(&boxes);
        let mut seen = [false; 100];
        for &p in &bvh.order {
            assert!(!seen[p as usize]);
            seen[p as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
        for k in 0..50 {
            let target = boxes[k * 2].centroid();
            let origin = Vec3::new(10.0, 0.5, 1.0);
            let dir = (target - origin).normalized();
            let brute = boxes
                .iter()
                .filter_map(|b| b.hit(origin, dir.recip(), f32::INFINITY))
                .fold(f32::INFINITY, f32::min);
            let got = bvh
                .closest(origin, dir, f32::INFINITY, |p, t_max| {
                    boxes[p as usize]
                        .hit(origin, dir.recip(), t_max)
                        .filter(|&t| t < t_max)
                })
                .unwrap();
            assert_eq!(got, brute);
            assert!(bvh.any(origin, dir, f32::INFINITY, |p| {
                boxes[p as usize]
                    .hit(origin, dir.recip(), f32::INFINITY)
                    .is_some()
            }));
        }
    }

    #[test]
    fn coincident_centroids_make_one_leaf() {
        let boxes = vec![unit_box(Vec3::ZERO); 10];
        let mut bvh = Bvh::new();
        bvh.build(&boxes);
        assert_eq!(bvh.node_count(), 1);
        bvh.build(&[]);
        assert!(
            bvh.closest(Vec3::ZERO, Vec3::ONE, 1.0, |_, _| Some(0.0))
                .is_none()
        );
    }
}
