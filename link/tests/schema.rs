//! The schema hash: recomputed from `postcard-schema`'s description of the request and
//! response types, and held to [`SCHEMA_HASH`], which every frame carries. Changing a
//! message (a field, a variant, a type, their order) changes the description, so this
//! fails until the constant is updated — and a device and a host built from different
//! schemas then tell each other so instead of decoding garbage.

use cuesight_link::{Request, Response, SCHEMA_HASH};
use postcard_schema::Schema;

/// FNV-1a, 32 bits.
fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5, |hash, &b| {
        (hash ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

fn schema_hash() -> u32 {
    let mut description = postcard::to_stdvec(Request::SCHEMA).expect("request schema");
    description.extend(postcard::to_stdvec(Response::SCHEMA).expect("response schema"));
    fnv1a(&description)
}

#[test]
fn schema_hash_is_the_schemas() {
    let hash = schema_hash();
    assert_eq!(
        SCHEMA_HASH, hash,
        "the link's schema changed: set SCHEMA_HASH = 0x{hash:08x} in link/src/limits.rs"
    );
}

#[test]
fn the_description_sees_a_field_change() {
    // A stand-in for the real types with one field renamed and one retyped: the
    // description (and so the hash) must differ, or the check above could not fail.
    #[derive(serde::Serialize, postcard_schema::Schema)]
    #[allow(dead_code)]
    struct A {
        speed: f32,
        cut: f32,
    }
    #[derive(serde::Serialize, postcard_schema::Schema)]
    #[allow(dead_code)]
    struct B {
        speed: f32,
        cut: f64,
    }
    let a = postcard::to_stdvec(A::SCHEMA).unwrap();
    let b = postcard::to_stdvec(B::SCHEMA).unwrap();
    assert_ne!(fnv1a(&a), fnv1a(&b));
}
