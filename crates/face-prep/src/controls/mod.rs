//! The controls stage: what each control of the rig is and how it is placed on the shell.
//!
//! - [`ids`]: the shared vocabulary (sides, jaw modes, lid actions); imports nothing.
//! - [`muscle_kind`]: the table of controls, one row each (id, name, side, twin, generator).
//! - one generator per kind: muscle bands from [`anatomy`] attachments ([`muscle_model`]),
//!   force-driven bands and the sphincter ([`force_controls`]), the lips' marginal part that
//!   rolls them in ([`lip_margin`]), the modiolus pins
//!   ([`modiolus`]), the jaw's rigid modes ([`jaw`]), the lip seal over the open jaw ([`lip_seal`]), the lids ([`eyelid`]), the teeth the deep
//!   layer slides on ([`teeth`]); the thesis's ten muscles ([`muscles`]) and its muscle file
//!   format ([`muscle_file`]).
//! - `dispatch`: the two places a control's generator is dispatched on (its elements, its
//!   pattern).
//! - `rig_parts`: the parts of a rig the rig-wide functions read (the rig itself is built
//!   from this stage, which does not name it).

pub mod anatomy;
pub(crate) mod dispatch;
pub mod eyelid;
pub mod force_controls;
pub mod ids;
pub mod jaw;
pub mod lip_margin;
pub mod lip_seal;
pub mod modiolus;
pub mod muscle_file;
pub mod muscle_kind;
pub mod muscle_model;
pub mod muscles;
pub(crate) mod rig_parts;
pub mod teeth;
