//! Serialization helpers for the device's answers: the bytes on the wire are serde's
//! own, the code is smaller.

use serde::Serializer;

/// An `f32` field as serde serializes it (`serialize_f32`, the same bytes), for
/// `#[serde(serialize_with)]` on the answers' `f32` fields: out of line, a field's call
/// is shorter than postcard's sequence inlined at each (192 B of the live image for
/// its 55 fields).
#[inline(never)]
pub(crate) fn f32_field<S: Serializer>(value: &f32, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_f32(*value)
}
