//! Response basis (thesis eq. 9.2): one precomputed solution per load group.

use glam::DVec3;

use crate::{
    BemError, Control, ElementKind, ElementKinds, LinearSystem, Loads, Material, Solution,
    SolveParams, SolveReport, SurfaceMesh,
};

/// A load pattern: `(element, value)`, the displacement of a displacement-prescribed element or
/// the traction on a traction-type one.
pub type DisplacementGroup = Vec<(usize, DVec3)>;

/// Responses of a linear elastic body to unit amplitudes of several displacement groups.
///
/// All elements marked prescribed keep zero displacement except where a group drives them; all
/// other elements are traction-free except where a group loads them with a traction (a force-
/// driven muscle). K is factorised once and every group is one right-hand side,
/// so any combination `Σ_k s_k · group_k` has the exact response `Σ_k s_k · response_k`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ResponseBasis {
    /// One solution per group (u on every element, t on every element; t = 0 on free ones).
    pub responses: Vec<Solution>,
    /// What the solver measured about the trustworthiness of the responses.
    #[serde(default)]
    pub report: SolveReport,
}

impl ResponseBasis {
    /// Computes the response of each group.
    ///
    /// A group's value on a prescribed element is that element's displacement, on any other
    /// element the traction on it. Fails with [`BemError::BadGroupElement`] when a group names
    /// an element that does not exist, and [`BemError::PureTraction`] when nothing is
    /// prescribed.
    ///
    /// ```
    /// use bem_core::{shapes, Control, Material, ResponseBasis, SolveParams};
    /// use glam::DVec3;
    /// let mesh = shapes::sphere(1, 1.0).unwrap();
    /// // lower half fixed, two top-ish elements driven
    /// let prescribed: Vec<bool> = mesh.centroids().iter().map(|c| c.z < 0.0).collect();
    /// let driven: Vec<usize> = (0..mesh.element_count()).filter(|&e| prescribed[e]).take(2).collect();
    /// let groups = vec![vec![(driven[0], DVec3::X)], vec![(driven[1], DVec3::Y)]];
    /// let m = Material::new(0.45, 1.0).unwrap();
    /// let basis = ResponseBasis::compute(&mesh, &m, &prescribed, &groups, &SolveParams::default(), &Control::default()).unwrap();
    /// let mix = basis.combine_displacement(&[0.5, -1.0]).unwrap();
    /// assert_eq!(mix.len(), mesh.element_count());
    /// ```
    ///
    /// Any [`ElementKind`] per element works too: sliding elements keep zero normal
    /// displacement and zero tangential traction except where a group sets a value (its normal
    /// part a normal displacement, the rest a tangential traction).
    pub fn compute<K: ElementKinds + ?Sized>(
        mesh: &SurfaceMesh,
        material: &Material,
        kinds: &K,
        groups: &[DisplacementGroup],
        params: &SolveParams,
        control: &Control<'_>,
    ) -> Result<Self, BemError> {
        let n = mesh.element_count();
        let kinds = kinds.kinds_of(n)?;
        let kinds: &[ElementKind] = &kinds;
        let mut loads = Loads::new(n, groups.len());
        for (g, group) in groups.iter().enumerate() {
            for &(element, value) in group {
                if element >= n {
                    return Err(BemError::BadGroupElement {
                        group: g,
                        element,
                        reason: "does not exist",
                    });
                }
                loads.set(element, g, value)?;
            }
        }
        let system = LinearSystem::assemble(mesh, material, kinds, &loads, params, control)?;
        let (responses, report) = system.solve_with_report(control)?;
        Ok(Self { responses, report })
    }

    /// Number of groups.
    pub fn len(&self) -> usize {
        self.responses.len()
    }

    /// Whether there is no group.
    pub fn is_empty(&self) -> bool {
        self.responses.is_empty()
    }

    /// Element displacements for amplitudes `s` (one per group): `Σ_k s_k u_k`.
    pub fn combine_displacement(&self, s: &[f64]) -> Result<Vec<DVec3>, BemError> {
        self.combine(s, |r| &r.displacement)
    }

    /// Element tractions for amplitudes `s` (one per group): `Σ_k s_k t_k`.
    pub fn combine_traction(&self, s: &[f64]) -> Result<Vec<DVec3>, BemError> {
        self.combine(s, |r| &r.traction)
    }

    fn combine(
        &self,
        s: &[f64],
        field: impl Fn(&Solution) -> &Vec<DVec3>,
    ) -> Result<Vec<DVec3>, BemError> {
        if s.len() != self.responses.len() {
            return Err(BemError::WrongLength {
                what: "amplitudes (one per group)",
                expected: self.responses.len(),
                got: s.len(),
            });
        }
        let n = self.responses.first().map_or(0, |r| field(r).len());
        let mut out = vec![DVec3::ZERO; n];
        for (r, &a) in self.responses.iter().zip(s) {
            for (o, v) in out.iter_mut().zip(field(r)) {
                *o += a * *v;
            }
        }
        Ok(out)
    }
}
