//! [`FileObject`]: an object as a scene file writes it: one of the core's shapes, or a mesh
//! file to read (`shape.mesh = { file = … }`), which the core's [`ShapeDesc`] cannot hold.

use crate::mesh_file::MeshFile;
use obscura::{MaterialDesc, ShapeDesc};
use serde::de::{
    self, DeserializeSeed, Deserializer, EnumAccess, IntoDeserializer, MapAccess, VariantAccess,
    Visitor,
};
use serde::{Deserialize, Serialize};
use std::fmt;

/// An object of a scene file.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FileObject {
    /// Its shape, or the mesh file that gives it.
    pub(crate) shape: FileShape,
    /// See [`obscura::ObjectDesc::material`].
    #[serde(default)]
    pub(crate) material: MaterialDesc,
}

/// A shape as a scene file writes it.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub(crate) enum FileShape {
    /// One of the core's.
    Shape(ShapeDesc),
    /// A mesh read from a file.
    Mesh {
        /// The file and where it is placed.
        mesh: MeshFile,
    },
}

/// The kinds of shape a scene file names, as it spells them.
const KINDS: &[&str] = &["sphere", "plane", "triangle", "mesh"];

impl<'de> Deserialize<'de> for FileShape {
    /// A table of one key, the kind: `mesh` reads a [`MeshFile`], any other is handed to the
    /// core's [`ShapeDesc`] as the variant it names, so that its fields are checked (and their
    /// mistakes placed) as they always are.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(ShapeVisitor)
    }
}

struct ShapeVisitor;

impl<'de> Visitor<'de> for ShapeVisitor {
    type Value = FileShape;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a shape: one of {}", KINDS.join(", "))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<FileShape, A::Error> {
        let Some(kind) = map.next_key::<String>()? else {
            return Err(de::Error::custom(format!(
                "a shape names its kind: one of {}",
                KINDS.join(", ")
            )));
        };
        let shape = match kind.as_str() {
            "mesh" => FileShape::Mesh {
                mesh: map.next_value()?,
            },
            _ if KINDS.contains(&kind.as_str()) => {
                FileShape::Shape(ShapeDesc::deserialize(Variant {
                    kind,
                    map: &mut map,
                })?)
            }
            _ => return Err(de::Error::unknown_variant(&kind, KINDS)),
        };
        if let Some(other) = map.next_key::<String>()? {
            return Err(de::Error::custom(format!(
                "a shape is of one kind, and this one is also `{other}`: give each its own object"
            )));
        }
        Ok(shape)
    }
}

/// The variant `kind` of an enum whose fields are the next value of `map`: how the core's
/// shape reads the table the file gives it.
struct Variant<'m, A> {
    kind: String,
    map: &'m mut A,
}

impl<'de, A: MapAccess<'de>> Deserializer<'de> for Variant<'_, A> {
    type Error = A::Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, A::Error> {
        visitor.visit_enum(self)
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map struct enum
        identifier ignored_any
    }
}

impl<'de, A: MapAccess<'de>> EnumAccess<'de> for Variant<'_, A> {
    type Error = A::Error;
    type Variant = Self;

    fn variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<(T::Value, Self), A::Error> {
        let kind: de::value::StrDeserializer<'_, A::Error> = self.kind.as_str().into_deserializer();
        let value = seed.deserialize(kind)?;
        Ok((value, self))
    }
}

impl<'de, A: MapAccess<'de>> VariantAccess<'de> for Variant<'_, A> {
    type Error = A::Error;

    fn unit_variant(self) -> Result<(), A::Error> {
        self.map.next_value::<de::IgnoredAny>().map(|_| ())
    }

    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, A::Error> {
        self.map.next_value_seed(seed)
    }

    fn tuple_variant<V: Visitor<'de>>(self, _: usize, visitor: V) -> Result<V::Value, A::Error> {
        self.map.next_value_seed(Fields {
            fields: &[],
            visitor,
        })
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, A::Error> {
        self.map.next_value_seed(Fields { fields, visitor })
    }
}

/// A variant's fields, read from the value that holds them.
struct Fields<V> {
    fields: &'static [&'static str],
    visitor: V,
}

impl<'de, V: Visitor<'de>> DeserializeSeed<'de> for Fields<V> {
    type Value = V::Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<V::Value, D::Error> {
        deserializer.deserialize_struct("shape", self.fields, self.visitor)
    }
}
