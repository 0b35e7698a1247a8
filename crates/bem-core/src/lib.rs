//! # bem-core: constant-element boundary element method for 3D linear elastostatics
//!
//! The boundary of an elastic body is a closed, outward-oriented triangle mesh ([`SurfaceMesh`]).
//! Every triangle is one constant element with its collocation node at the centroid and three
//! unknowns; each element has either its displacement or its traction prescribed
//! ([`BoundaryCondition`]). The boundary integral equation `H u = G t` uses the Kelvin kernels
//! ([`kernels`]), a 7-point triangle rule refined by adaptive 1→4 subdivision for near pairs
//! down to a depth derived from each pair's gap and the tolerance, reporting the blocks that
//! could not reach it ([`QuadratureParams`], [`AssemblyReport`]), the analytic singular G
//! block ([`singular`]) and the rigid-body row sum for the diagonal H blocks. The mixed system `K x = y` is assembled directly, column block by
//! column block in parallel ([`LinearSystem::assemble`]), and solved with a blocked dense LU with
//! partial pivoting built on faer's kernels ([`DenseLu`]) for many right-hand sides at once;
//! by default K above [`MIXED_MIN_UNKNOWNS`] unknowns is factorised in f32 and the answer
//! refined to f64 accuracy ([`MixedLu`], [`Precision`]).
//! Both stages report progress and can be cancelled ([`Control`]). [`ResponseBasis`]
//! precomputes the response to each of several displacement groups so that any combination is an
//! exact linear sum.
//!
//! Memory: one dense K (8·(3N)² bytes) plus the right-hand sides and (threads + 1)·3N·(load
//! cases) doubles of assembly buffers ([`MemoryEstimate`]); H and G are never held. The total is
//! checked against a budget before anything large is allocated ([`BemError::OverBudget`]).
//! Benchmark (assembly, LU rate, peak memory at ~1000/3000/5000 elements):
//! `cargo run --release -p bem-core --example bench`.
//!
//! ## Example: hollow sphere with a prescribed radial displacement inside
//!
//! ```
//! use bem_core::{shapes, solve, BoundaryCondition, Control, Material, SolveParams, element_to_vertex};
//!
//! // a = 1, b = 2; 80 + 80 elements; inner elements come first
//! let mesh = shapes::hollow_sphere(1.0, 2.0, 1).unwrap();
//! let n_inner = mesh.element_count() / 2;
//! let bcs: Vec<BoundaryCondition> = (0..mesh.element_count())
//!     .map(|e| if e < n_inner {
//!         BoundaryCondition::Displacement(0.01 * mesh.centroid(e).normalize())
//!     } else {
//!         BoundaryCondition::FREE
//!     })
//!     .collect();
//! let material = Material::new(0.3, 1.0).unwrap();
//! let solution = solve(&mesh, &material, &bcs, &SolveParams::default(), &Control::default()).unwrap();
//! // the outer surface moves outward, less than the inner one
//! let outer = &solution.displacement[n_inner..];
//! let mean_ur: f64 = outer.iter().zip(&mesh.centroids()[n_inner..])
//!     .map(|(u, x)| u.dot(x.normalize())).sum::<f64>() / outer.len() as f64;
//! assert!(mean_ur > 0.0 && mean_ur < 0.01);
//! let per_vertex = element_to_vertex(&mesh, &solution.displacement).unwrap();
//! assert_eq!(per_vertex.len(), mesh.vertices().len());
//! ```

mod assembly;
mod assembly_report;
mod bc;
mod bodies;
mod budget;
mod column;
mod control;
pub mod dense;
mod error;
pub mod kernels;
mod material;
mod matrix;
mod mesh;
mod mixed;
mod naive;
mod params;
pub mod quadrature;
mod response;
pub mod shapes;
pub mod singular;
mod solve;
mod vertex;

pub use assembly::LinearSystem;
pub use assembly_report::{AssemblyReport, UnconvergedBlock};
pub use bc::{BoundaryCondition, ElementKind, ElementKinds, Loads, tangent_frame};
pub use budget::MemoryEstimate;
pub use control::{Control, Progress, Stage};
pub use dense::DenseLu;
pub use error::{BemError, MeshError};
pub use material::Material;
pub use matrix::DenseMatrix;
pub use mesh::SurfaceMesh;
pub use mixed::{MAX_MIXED_CONDITION, MIXED_MIN_UNKNOWNS, MixedLu};
pub use naive::assemble_h_g;
pub use params::{DEFAULT_MAX_CONDITION, Precision, RigidModes, SolveParams};
pub use quadrature::QuadratureParams;
pub use response::{DisplacementGroup, ResponseBasis};
pub use solve::{Solution, SolveReport, solve};
pub use vertex::{element_to_vertex, element_to_vertex_linear};

pub use faer;
pub use glam;
