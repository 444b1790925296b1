//! What the pilot asks of a traced path: the same path as a cheaper setting would have
//! traced it (fewer bounces, fewer sky-view rays), so that one trace at the reference is
//! evaluated under every setting.

use crate::path::{Diffuse, Escape, HemiRay, Mirror, Path};

impl Path {
    /// This path with at most `bounces` specular bounces, into `out`: what a rendering with
    /// that limit records (the last facet reflects its untraced environment).
    pub(crate) fn truncated(&self, bounces: u32, out: &mut Path) {
        out.primary = self.primary;
        out.rays.clone_from(&self.rays);
        out.nodes.clear();
        let keep = (bounces as usize + 1).min(self.nodes.len());
        out.nodes.extend_from_slice(&self.nodes[..keep]);
        if let Some(last) = out.nodes.last_mut()
            && keep == bounces as usize + 1
            && last.mirror.is_some()
        {
            last.mirror = Some(Mirror::Untraced(last.environment));
        }
    }

    /// This path with only the first `n` of its first facet's sky-view rays (0: F = 1).
    pub(crate) fn with_sky_rays(&self, n: u32, out: &mut Path) {
        out.clone_from(self);
        if let Some(node) = out.nodes.first_mut()
            && let Some(Diffuse::Rays { start, count, .. }) = node.diffuse
        {
            let n = n.min(count);
            node.diffuse = Some(if n == 0 {
                Diffuse::Hemispheric
            } else {
                let rays = &self.rays[start as usize..(start + n) as usize];
                let sky = rays
                    .iter()
                    .filter(|r| matches!(r, HemiRay::Escaped(Escape::Sky { zenith_deg, .. }) if *zenith_deg <= 90.0))
                    .count() as u32;
                Diffuse::Rays {
                    start,
                    count: n,
                    sky,
                }
            });
        }
    }

    /// Whether its first facet cast sky-view rays.
    pub(crate) fn has_sky_view_rays(&self) -> bool {
        self.nodes
            .first()
            .is_some_and(|n| matches!(n.diffuse, Some(Diffuse::Rays { count, .. }) if count > 0))
    }

    /// Reflection rays this path traced within `bounces` bounces.
    pub(crate) fn reflection_rays(&self, bounces: u32) -> u32 {
        let traced = self
            .nodes
            .iter()
            .take(bounces as usize)
            .filter(|n| matches!(n.mirror, Some(Mirror::Next | Mirror::Escaped(_))))
            .count();
        traced as u32
    }
}
