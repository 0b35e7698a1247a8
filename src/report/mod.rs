//! Reports about a computed face, off the production path: a text description for `info`
//! ([`describe`]), measurements in millimetres against human motion for tests and calibration
//! ([`measure`]), the whole head against ICT-FaceKit's captures ([`captures`]), and
//! contact-sheet images ([`contact_sheet`]).

pub mod captures;
pub mod contact_sheet;
pub mod describe;
pub mod measure;
