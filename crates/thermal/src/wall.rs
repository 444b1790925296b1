//! A facet's wall cut into finite volumes.
//!
//! The scheme is vertex-centred ("node at surface"): a node sits on the exposed surface, one
//! on the back face, one on every interface between two layers, and others inside each
//! layer, so that every cell (the stretch between two neighbouring nodes) lies inside one
//! layer. A node owns half of each cell beside it: its heat capacity per unit area is
//! `Σ ρ c Δx / 2` over those halves (an interface node takes half a cell of each layer), and
//! two neighbours are joined by the conductance `k / Δx` of the cell between them. Because
//! no cell straddles an interface, the series resistance of two layers is the sum of their
//! cells' resistances `Δx / k` and no averaging of conductivities is needed; a steady,
//! piecewise-linear profile is represented exactly, and the scheme is second-order in the
//! node spacing (Patankar 1980, *Numerical Heat Transfer and Fluid Flow*, §4.2 and §4.6:
//! his practice A, grid points first and faces midway, with the boundary and interface
//! half control volumes of his §4.2-9). The surface node's temperature is the surface
//! temperature the energy balance and the sensor see, with no extrapolation.

use std::sync::atomic::{AtomicU64, Ordering};

use irsig_model::thermal::{BackBoundary, ThermalProperties};

use crate::error::ThermalError;

/// The most nodes a wall may have.
pub const MAX_NODES: usize = 100_000;

/// How a wall is cut into cells, layer by layer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeSpacing {
    /// The same number of equal cells in every layer (at least 1).
    CellsPerLayer(usize),
    /// Equal cells in each layer, no longer than `max_spacing_m`, and at least
    /// `min_cells_per_layer` of them (at least 1).
    MaxSpacing {
        /// The longest cell, metres.
        max_spacing_m: f64,
        /// The fewest cells in any layer, however thin.
        min_cells_per_layer: usize,
    },
    /// Geometric refinement toward the exposed surface, where a diurnal cycle's gradients
    /// are steepest: the cell at the surface is `first_cell_m` long, each cell deeper is
    /// `growth` times the one before it (across interfaces too) until `max_spacing_m`, then
    /// they stay that long. Each layer's cells are then scaled down together so that they
    /// fill the layer exactly (a layer thinner than its first planned cell gets one cell).
    Graded {
        /// The cell at the exposed surface, metres.
        first_cell_m: f64,
        /// The ratio of a cell to the one in front of it, 1 (uniform) to 10.
        growth: f64,
        /// The longest cell, metres (at least `first_cell_m`).
        max_spacing_m: f64,
    },
}

/// How a wall is discretised.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Discretisation {
    /// How the layers are cut into cells.
    pub nodes: NodeSpacing,
}

impl Discretisation {
    /// `n` equal cells per layer.
    #[must_use]
    pub fn cells_per_layer(n: usize) -> Self {
        Self {
            nodes: NodeSpacing::CellsPerLayer(n),
        }
    }

    /// Equal cells at most `max_spacing_m` long, at least `min_cells_per_layer` per layer.
    #[must_use]
    pub fn max_spacing(max_spacing_m: f64, min_cells_per_layer: usize) -> Self {
        Self {
            nodes: NodeSpacing::MaxSpacing {
                max_spacing_m,
                min_cells_per_layer,
            },
        }
    }

    /// Cells growing geometrically from `first_cell_m` at the surface up to `max_spacing_m`.
    #[must_use]
    pub fn graded(first_cell_m: f64, growth: f64, max_spacing_m: f64) -> Self {
        Self {
            nodes: NodeSpacing::Graded {
                first_cell_m,
                growth,
                max_spacing_m,
            },
        }
    }

    /// The cell lengths of each layer, front first, checked against [`MAX_NODES`].
    fn cells(&self, thicknesses_m: &[f64]) -> Result<Vec<Vec<f64>>, ThermalError> {
        let too_many = |n: f64| {
            ThermalError::wall(format!(
                "{self:?} needs {n} cells: at most {MAX_NODES} nodes are accepted"
            ))
        };
        match self.nodes {
            NodeSpacing::CellsPerLayer(n) => {
                if n == 0 {
                    return Err(ThermalError::wall("a layer needs at least 1 cell"));
                }
                let total = n as f64 * thicknesses_m.len() as f64;
                if total >= MAX_NODES as f64 {
                    return Err(too_many(total));
                }
                Ok(thicknesses_m
                    .iter()
                    .map(|&l| vec![l / n as f64; n])
                    .collect())
            }
            NodeSpacing::MaxSpacing {
                max_spacing_m,
                min_cells_per_layer,
            } => {
                if !(max_spacing_m.is_finite() && max_spacing_m > 0.0) {
                    return Err(ThermalError::wall(format!(
                        "max_spacing_m {max_spacing_m} must be a positive length in metres"
                    )));
                }
                if min_cells_per_layer == 0 {
                    return Err(ThermalError::wall("a layer needs at least 1 cell"));
                }
                let counts: Vec<f64> = thicknesses_m
                    .iter()
                    .map(|&l| (l / max_spacing_m).ceil().max(min_cells_per_layer as f64))
                    .collect();
                let total: f64 = counts.iter().sum();
                if total >= MAX_NODES as f64 {
                    return Err(too_many(total));
                }
                Ok(thicknesses_m
                    .iter()
                    .zip(&counts)
                    .map(|(&l, &n)| {
                        // `n` is below MAX_NODES, so the cast is exact.
                        let n = n as usize;
                        vec![l / n as f64; n]
                    })
                    .collect())
            }
            NodeSpacing::Graded {
                first_cell_m,
                growth,
                max_spacing_m,
            } => graded_cells(thicknesses_m, first_cell_m, growth, max_spacing_m),
        }
    }
}

/// The cells of [`NodeSpacing::Graded`].
fn graded_cells(
    thicknesses_m: &[f64],
    first_cell_m: f64,
    growth: f64,
    max_spacing_m: f64,
) -> Result<Vec<Vec<f64>>, ThermalError> {
    if !(first_cell_m.is_finite() && first_cell_m > 0.0) {
        return Err(ThermalError::wall(format!(
            "first_cell_m {first_cell_m} must be a positive length in metres"
        )));
    }
    if !(1.0..=10.0).contains(&growth) {
        return Err(ThermalError::wall(format!(
            "growth {growth} must lie between 1 (uniform) and 10"
        )));
    }
    if !(max_spacing_m.is_finite() && max_spacing_m >= first_cell_m) {
        return Err(ThermalError::wall(format!(
            "max_spacing_m {max_spacing_m} must be a length of at least first_cell_m \
             {first_cell_m}"
        )));
    }
    let mut planned = first_cell_m;
    let mut total = 0usize;
    let mut layers = Vec::with_capacity(thicknesses_m.len());
    for &thickness in thicknesses_m {
        let mut cells = Vec::new();
        let mut sum = 0.0;
        while sum < thickness {
            cells.push(planned);
            sum += planned;
            planned = (planned * growth).min(max_spacing_m);
            total += 1;
            if total >= MAX_NODES {
                return Err(ThermalError::wall(format!(
                    "cells from {first_cell_m} m growing by {growth} up to {max_spacing_m} m \
                     need more than {MAX_NODES} nodes for this wall"
                )));
            }
        }
        let scale = thickness / sum;
        cells.iter_mut().for_each(|c| *c *= scale);
        layers.push(cells);
    }
    Ok(layers)
}

/// A wall cut into finite volumes: node depths, heat capacities, conductances and the back
/// boundary. Built once per material and discretisation, shared by every facet of that
/// material; immutable.
#[derive(Debug, Clone)]
pub struct Wall {
    /// Unique per construction, so a [`crate::Scratch`] can cache what it derives from it.
    id: u64,
    depths_m: Vec<f64>,
    capacity_j_m2_k: Vec<f64>,
    conductance_w_m2_k: Vec<f64>,
    back: BackBoundary,
}

static NEXT_WALL_ID: AtomicU64 = AtomicU64::new(0);

impl Wall {
    /// Cuts a material's wall into nodes.
    ///
    /// # Errors
    /// [`crate::ThermalErrorKind::InvalidWall`] when the record breaks one of its rules
    /// (`ThermalProperties::validate`), the spacing is not usable, or the wall would need
    /// more than [`MAX_NODES`] nodes.
    pub fn new(props: &ThermalProperties, disc: &Discretisation) -> Result<Self, ThermalError> {
        props
            .validate("thermal")
            .map_err(|e| ThermalError::wall(e.to_string()))?;
        let thicknesses: Vec<f64> = props.layers.iter().map(|l| l.thickness_m).collect();
        let cells = disc.cells(&thicknesses)?;
        let n_nodes = 1 + cells.iter().map(Vec::len).sum::<usize>();
        let mut depths_m = Vec::with_capacity(n_nodes);
        let mut capacity_j_m2_k = vec![0.0; n_nodes];
        let mut conductance_w_m2_k = Vec::with_capacity(n_nodes - 1);
        depths_m.push(0.0);
        let mut node = 0;
        let mut depth = 0.0;
        for (layer, layer_cells) in props.layers.iter().zip(&cells) {
            let rho_c = layer.density_kg_m3 * layer.specific_heat_j_kg_k;
            for &dx in layer_cells {
                let half = 0.5 * rho_c * dx;
                capacity_j_m2_k[node] += half;
                capacity_j_m2_k[node + 1] += half;
                conductance_w_m2_k.push(layer.conductivity_w_m_k / dx);
                depth += dx;
                depths_m.push(depth);
                node += 1;
            }
        }
        Ok(Self {
            id: NEXT_WALL_ID.fetch_add(1, Ordering::Relaxed),
            depths_m,
            capacity_j_m2_k,
            conductance_w_m2_k,
            back: props.back,
        })
    }

    /// The number of nodes (temperatures) of the wall, surface first.
    #[must_use]
    pub fn nodes(&self) -> usize {
        self.depths_m.len()
    }

    /// Each node's depth below the exposed surface, metres: 0 first, the wall's thickness
    /// last.
    #[must_use]
    pub fn depths_m(&self) -> &[f64] {
        &self.depths_m
    }

    /// Each node's heat capacity per unit area, J m⁻² K⁻¹.
    #[must_use]
    pub fn capacities_j_m2_k(&self) -> &[f64] {
        &self.capacity_j_m2_k
    }

    /// The conductance between node `i` and node `i + 1`, W m⁻² K⁻¹ (one fewer than the
    /// nodes).
    #[must_use]
    pub fn conductances_w_m2_k(&self) -> &[f64] {
        &self.conductance_w_m2_k
    }

    /// What lies behind the last node.
    #[must_use]
    pub fn back(&self) -> BackBoundary {
        self.back
    }

    /// The heat the wall holds per unit area above 0 K, `Σ C_i T_i`, J m⁻², over the pairs of
    /// capacities and temperatures that exist (a `temps` of another length than
    /// [`Wall::nodes`] is summed as far as both go). For checking energy closure.
    #[must_use]
    pub fn stored_energy_j_m2(&self, temps: &[f64]) -> f64 {
        self.capacity_j_m2_k
            .iter()
            .zip(temps)
            .map(|(c, t)| c * t)
            .sum()
    }

    /// A uniform initial state: every node at `temperature_k`.
    #[must_use]
    pub fn uniform_state(&self, temperature_k: f64) -> Vec<f64> {
        vec![temperature_k; self.nodes()]
    }

    pub(crate) fn id(&self) -> u64 {
        self.id
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::thermal::{Roughness, ThermalLayer};

    fn layer(thickness_m: f64, k: f64, rho: f64, c: f64) -> ThermalLayer {
        ThermalLayer {
            thickness_m,
            conductivity_w_m_k: k,
            density_kg_m3: rho,
            specific_heat_j_kg_k: c,
            source: "test".into(),
        }
    }

    fn props(layers: Vec<ThermalLayer>) -> ThermalProperties {
        ThermalProperties {
            layers,
            back: BackBoundary::Adiabatic,
            solar_absorptance: Some(0.5),
            thermal_emissivity: Some(0.9),
            wet_fraction: 0.0,
            roughness: Roughness::default(),
            source: "test".into(),
        }
    }

    #[test]
    fn two_layers_by_hand() {
        // 0.02 m of k=1, ρc=2e6 in 2 cells, then 0.1 m of k=0.5, ρc=1e6 in 2 cells.
        let p = props(vec![
            layer(0.02, 1.0, 1000.0, 2000.0),
            layer(0.1, 0.5, 1000.0, 1000.0),
        ]);
        let w = Wall::new(&p, &Discretisation::cells_per_layer(2)).unwrap();
        assert_eq!(w.nodes(), 5);
        let d = w.depths_m();
        for (got, want) in d.iter().zip([0.0, 0.01, 0.02, 0.07, 0.12]) {
            assert!((got - want).abs() < 1e-15, "{d:?}");
        }
        // Half cells: 2e6·0.005 = 1e4; interface 1e4 + 1e6·0.025 = 3.5e4; 1e6·0.025 = 2.5e4.
        let c = w.capacities_j_m2_k();
        for (got, want) in c.iter().zip([1e4, 2e4, 3.5e4, 5e4, 2.5e4]) {
            assert!((got - want).abs() < 1e-9, "{c:?}");
        }
        // k/Δx: 1/0.01 = 100 twice, 0.5/0.05 = 10 twice.
        let g = w.conductances_w_m2_k();
        for (got, want) in g.iter().zip([100.0, 100.0, 10.0, 10.0]) {
            assert!((got - want).abs() < 1e-9, "{g:?}");
        }
        // Σ C = ρc L over the wall: 2e6·0.02 + 1e6·0.1 = 1.4e5.
        assert!((w.stored_energy_j_m2(&w.uniform_state(1.0)) - 1.4e5).abs() < 1e-6);
    }

    #[test]
    fn series_resistance_is_the_sum_of_the_layers() {
        let p = props(vec![
            layer(0.05, 1.4, 2300.0, 880.0),
            layer(0.1, 0.04, 30.0, 1400.0),
            layer(0.01, 0.16, 800.0, 1000.0),
        ]);
        for disc in [
            Discretisation::cells_per_layer(3),
            Discretisation::max_spacing(0.004, 2),
            Discretisation::graded(1e-3, 1.3, 0.02),
        ] {
            let w = Wall::new(&p, &disc).unwrap();
            let r: f64 = w.conductances_w_m2_k().iter().map(|g| 1.0 / g).sum();
            let want = 0.05 / 1.4 + 0.1 / 0.04 + 0.01 / 0.16;
            assert!((r - want).abs() < 1e-12 * want, "{disc:?}: {r} vs {want}");
            let total = w.stored_energy_j_m2(&w.uniform_state(1.0));
            let want = 0.05 * 2300.0 * 880.0 + 0.1 * 30.0 * 1400.0 + 0.01 * 800.0 * 1000.0;
            assert!((total - want).abs() < 1e-9 * want, "{disc:?}");
            assert!((w.depths_m()[w.nodes() - 1] - 0.16).abs() < 1e-15);
        }
    }

    #[test]
    fn max_spacing_and_grading_keep_their_promises() {
        let p = props(vec![
            layer(1e-6, 0.2, 1200.0, 1500.0),
            layer(0.2, 1.4, 2300.0, 880.0),
        ]);
        let w = Wall::new(&p, &Discretisation::max_spacing(0.01, 2)).unwrap();
        // 2 cells of paint, 20 of concrete.
        assert_eq!(w.nodes(), 23);
        let w = Wall::new(&p, &Discretisation::graded(1e-3, 1.5, 0.02)).unwrap();
        let d = w.depths_m();
        let cells: Vec<f64> = d.windows(2).map(|p| p[1] - p[0]).collect();
        assert!(cells.iter().all(|&c| c <= 0.02 + 1e-15), "{cells:?}");
        // Inside the concrete, each cell is at most 1.5 times the one before it.
        assert!(
            cells[1..]
                .windows(2)
                .all(|p| p[1] <= 1.5 * p[0] * (1.0 + 1e-12))
        );
        assert!((d[1] - 1e-6).abs() < 1e-18);
    }

    #[test]
    fn unusable_discretisations_are_errors() {
        let p = props(vec![layer(100.0, 1.4, 2300.0, 880.0)]);
        for disc in [
            Discretisation::cells_per_layer(0),
            Discretisation::cells_per_layer(usize::MAX),
            Discretisation::max_spacing(0.0, 1),
            Discretisation::max_spacing(f64::NAN, 1),
            Discretisation::max_spacing(1e-9, 1),
            Discretisation::max_spacing(0.1, 0),
            Discretisation::graded(1e-12, 1.0, 1.0),
            Discretisation::graded(1e-3, 0.5, 1.0),
            Discretisation::graded(1e-3, 1.2, 1e-4),
            Discretisation::graded(f64::INFINITY, 1.2, 1.0),
        ] {
            let e = Wall::new(&p, &disc).unwrap_err();
            assert_eq!(e.kind, crate::ThermalErrorKind::InvalidWall, "{disc:?}");
        }
        let mut bad = props(vec![layer(0.0, 1.4, 2300.0, 880.0)]);
        let e = Wall::new(&bad, &Discretisation::cells_per_layer(2)).unwrap_err();
        assert!(e.message.contains("thermal.layers[0].thickness_m"), "{e}");
        bad.layers.clear();
        assert!(Wall::new(&bad, &Discretisation::cells_per_layer(2)).is_err());
    }
}
