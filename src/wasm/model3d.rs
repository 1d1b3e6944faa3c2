//! The 3D world in the browser: `worldGlb` on a saved world, and the height options that
//! `Mapper.worldGlb` shares. The model is [`crate::render::model3d`]'s.

use crate::floorplan::World;
use crate::render::model3d::{world_glb as glb, Model3dOptions};
use serde::Deserialize;
use wasm_bindgen::prelude::*;

/// The heights as JavaScript names them.
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(default, deny_unknown_fields, rename_all = "camelCase")]
struct Heights {
    wall_height: Option<f64>,
    door_height: Option<f64>,
}

/// Reads `{ wallHeight?, doorHeight? }` (metres; `undefined` or `null`: the defaults).
pub(crate) fn options(v: Option<&JsValue>) -> Result<Model3dOptions, JsError> {
    let d = Model3dOptions::default();
    let Some(v) = v.filter(|v| !v.is_undefined() && !v.is_null()) else {
        return Ok(d);
    };
    if !v.is_object() {
        return Err(JsError::new("options: expected an object such as { wallHeight: 2.5, doorHeight: 2.0 }"));
    }
    let h: Heights = super::from_object(v)
        .map_err(|e| JsError::new(&format!("options: {e} (wallHeight and doorHeight are numbers of metres)")))?;
    let o = Model3dOptions {
        wall_height: h.wall_height.unwrap_or(d.wall_height),
        door_height: h.door_height.unwrap_or(d.door_height),
    };
    o.validate()?;
    Ok(o)
}

/// A saved world (`world.json`) in 3D, as `ksmcmc floorplan` writes `world.glb`:
/// `resolution` is the map's metres per cell, `options` the heights as for `Mapper.worldGlb`.
#[wasm_bindgen(js_name = worldGlb)]
pub fn world_glb(
    #[wasm_bindgen(js_name = worldJson)] world_json: &str,
    resolution: f64,
    #[wasm_bindgen(unchecked_optional_param_type = "{ wallHeight?: number; doorHeight?: number }")] options: Option<
        JsValue,
    >,
) -> Result<Vec<u8>, JsError> {
    let world = World::from_json(world_json)?;
    Ok(glb(&world, resolution, &self::options(options.as_ref())?)?)
}
