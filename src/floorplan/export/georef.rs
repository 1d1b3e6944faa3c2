//! Where a map lies: from map cells to metres in the map's own frame (the ROS origin of its
//! `map.yaml`), and from there to longitude and latitude when the user says where the map is
//! on the Earth (a [`Georef`]). The GeoJSON export ([`super::geojson`]) writes coordinates with
//! these.
//!
//! # Metres
//!
//! ROS's map_server puts the lower-left corner of the image at `origin = [x, y, yaw]` of the
//! map frame, `resolution` metres per cell, x to the right and y *up* the image. A point `(mx,
//! my)` in cells (x right, y down from the top-left corner, as [`super::shapes`] gives them) is
//! `(u, v) = (mx, height - my) * resolution` from that corner, turned by `yaw` and moved to
//! `(x, y)`. Plain images without a `map.yaml` have 5 cm cells and origin `[0, 0, 0]`.
//!
//! # Longitude and latitude
//!
//! A georeference `LAT,LON,BEARING` puts the map frame's origin (metres `(0, 0)`) at latitude
//! `LAT` and longitude `LON` (degrees, WGS 84), with the map frame's y axis pointing `BEARING`
//! degrees clockwise from true north (0: the map's up is north; 90: the map's up is east).
//! Points are projected on the local tangent plane at that place (an equirectangular
//! projection with the WGS 84 ellipsoid's radii of curvature there): over the few hundred
//! metres of a building the error is far below a map cell (millimetres at 1 km). Maps that
//! straddle the antimeridian keep longitudes beyond ±180 rather than being cut in two.
//!
//! ```
//! use ksmcmc::floorplan::georef::Georef;
//! let g: Georef = "53.1059, 8.8521, 90".parse().unwrap();
//! // 100 m along the map's y axis, which points east: the longitude grows, the latitude stays.
//! let (lon, lat) = g.lon_lat(0.0, 100.0);
//! assert!((lat - 53.1059).abs() < 1e-9 && (lon - 8.853_593_1).abs() < 1e-7, "{lon} {lat}");
//! assert!("53.1,8.8".parse::<Georef>().unwrap_err().to_string().contains("LAT,LON,BEARING"));
//! assert!("91,8.8,0".parse::<Georef>().is_err());
//! ```

use super::shapes::MapPoint;
use crate::grid::OccupancyMap;

/// How map cells become metres in the map's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapOrigin {
    /// Metres per cell.
    pub resolution: f64,
    /// The pose of the image's lower-left corner in the map frame: x, y (metres), yaw (radians).
    pub origin: [f64; 3],
    /// The map's height in cells.
    pub height: u32,
}

impl MapOrigin {
    /// The resolution and origin of `map` (its `map.yaml`, or the defaults of a plain image).
    pub fn of(map: &OccupancyMap) -> MapOrigin {
        let y = map.yaml();
        MapOrigin { resolution: y.resolution, origin: y.origin, height: map.height() as u32 }
    }

    /// A map point (cells, y down) in metres of the map frame (y up).
    pub fn to_metres(&self, (mx, my): MapPoint) -> (f64, f64) {
        let (u, v) = (mx * self.resolution, (self.height as f64 - my) * self.resolution);
        let [x, y, yaw] = self.origin;
        if yaw == 0.0 {
            return (x + u, y + v);
        }
        let (s, c) = (libm::sin(yaw), libm::cos(yaw));
        (x + c * u - s * v, y + s * u + c * v)
    }
}

/// Where the map frame lies on the Earth: see the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Georef {
    /// Latitude of the map frame's origin, degrees north.
    pub lat: f64,
    /// Longitude of the map frame's origin, degrees east.
    pub lon: f64,
    /// Direction of the map frame's y axis, degrees clockwise from true north.
    pub bearing: f64,
}

/// Why a georeference was refused.
#[derive(Debug, Clone, PartialEq)]
pub enum GeorefError {
    /// The text is not three numbers separated by commas.
    Format(String),
    /// The latitude is not a number from -89 to 89 degrees.
    Latitude(f64),
    /// The longitude is not a number from -180 to 180 degrees.
    Longitude(f64),
    /// The bearing is not a number from -360 to 360 degrees.
    Bearing(f64),
}

impl std::fmt::Display for GeorefError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        const HOW: &str = "a georeference is LAT,LON,BEARING in degrees: the latitude and longitude of \
                           the map frame's origin and the compass bearing of the map's y axis, e.g. \
                           53.1059,8.8521,0";
        match self {
            GeorefError::Format(text) => write!(f, "{text:?} is not three numbers separated by commas; {HOW}"),
            GeorefError::Latitude(v) => {
                write!(f, "latitude {v} is not between -89 and 89 degrees (the local plane fails at the poles); {HOW}")
            }
            GeorefError::Longitude(v) => write!(f, "longitude {v} is not between -180 and 180 degrees; {HOW}"),
            GeorefError::Bearing(v) => write!(f, "bearing {v} is not between -360 and 360 degrees; {HOW}"),
        }
    }
}

impl std::error::Error for GeorefError {}

/// WGS 84: semi-major axis (m) and first eccentricity squared.
const WGS84_A: f64 = 6_378_137.0;
const WGS84_E2: f64 = 0.006_694_379_990_141_316;

impl Georef {
    /// A checked georeference.
    pub fn new(lat: f64, lon: f64, bearing: f64) -> Result<Georef, GeorefError> {
        if !(lat.is_finite() && (-89.0..=89.0).contains(&lat)) {
            return Err(GeorefError::Latitude(lat));
        }
        if !(lon.is_finite() && (-180.0..=180.0).contains(&lon)) {
            return Err(GeorefError::Longitude(lon));
        }
        if !(bearing.is_finite() && (-360.0..=360.0).contains(&bearing)) {
            return Err(GeorefError::Bearing(bearing));
        }
        Ok(Georef { lat, lon, bearing })
    }

    /// Longitude and latitude (degrees) of the point `(x, y)` metres in the map frame.
    pub fn lon_lat(&self, x: f64, y: f64) -> (f64, f64) {
        let b = self.bearing.to_radians();
        let (sb, cb) = (libm::sin(b), libm::cos(b));
        let east = x * cb + y * sb;
        let north = -x * sb + y * cb;
        let phi = self.lat.to_radians();
        let (sp, cp) = (libm::sin(phi), libm::cos(phi));
        let w = 1.0 - WGS84_E2 * sp * sp;
        let meridian = WGS84_A * (1.0 - WGS84_E2) / (w * libm::sqrt(w));
        let normal = WGS84_A / libm::sqrt(w);
        (self.lon + (east / (normal * cp)).to_degrees(), self.lat + (north / meridian).to_degrees())
    }
}

impl std::str::FromStr for Georef {
    type Err = GeorefError;

    /// `LAT,LON,BEARING`, degrees, spaces allowed around the numbers.
    fn from_str(text: &str) -> Result<Georef, GeorefError> {
        let parts: Vec<&str> = text.split(',').map(str::trim).collect();
        let numbers: Option<Vec<f64>> = parts.iter().map(|p| p.parse::<f64>().ok()).collect();
        match numbers.as_deref() {
            Some(&[lat, lon, bearing]) => Georef::new(lat, lon, bearing),
            _ => Err(GeorefError::Format(text.chars().take(80).collect())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metres_follow_the_ros_origin_with_y_up() {
        let o = MapOrigin { resolution: 0.05, origin: [-12.0, -8.0, 0.0], height: 100 };
        // The top-left corner is `height` cells above the origin corner.
        assert_eq!(o.to_metres((0.0, 0.0)), (-12.0, -3.0));
        assert_eq!(o.to_metres((20.0, 100.0)), (-11.0, -8.0));
        let turned = MapOrigin { origin: [1.0, 2.0, std::f64::consts::FRAC_PI_2], ..o };
        let (x, y) = turned.to_metres((20.0, 100.0));
        assert!((x - 1.0).abs() < 1e-12 && (y - 3.0).abs() < 1e-12, "{x} {y}");
    }

    #[test]
    fn a_metre_north_and_east_at_the_equator_and_at_60_degrees() {
        let g = Georef::new(0.0, 10.0, 0.0).unwrap();
        let (lon, lat) = g.lon_lat(1000.0, 1000.0);
        // 1 km is 0.0090437 degrees of latitude at the equator and 0.0089832 of longitude.
        assert!((lat - 0.009_043_7).abs() < 1e-7 && (lon - 10.008_983_2).abs() < 1e-7, "{lon} {lat}");
        let g = Georef::new(60.0, 0.0, 0.0).unwrap();
        let (lon, _) = g.lon_lat(1000.0, 0.0);
        assert!((lon - 0.017_921_1).abs() < 1e-7, "a degree of longitude is half as long at 60 N: {lon}");
        // Bearing 180: the map's y axis points south.
        let (_, lat) = Georef::new(60.0, 0.0, 180.0).unwrap().lon_lat(0.0, 1000.0);
        assert!(lat < 60.0);
    }

    #[test]
    fn bad_georeferences_say_what_is_wrong() {
        let e = |t: &str| t.parse::<Georef>().unwrap_err();
        assert_eq!(e("53.1,8.8"), GeorefError::Format("53.1,8.8".into()));
        assert_eq!(e("a,b,c"), GeorefError::Format("a,b,c".into()));
        assert_eq!(e("95,8,0"), GeorefError::Latitude(95.0));
        assert!(matches!(e("NaN,8,0"), GeorefError::Latitude(v) if v.is_nan()));
        assert_eq!(e("50,181,0"), GeorefError::Longitude(181.0));
        assert_eq!(e("50,8,400"), GeorefError::Bearing(400.0));
        assert!(e("50,8,inf").to_string().contains("bearing inf is not between -360 and 360"));
        assert_eq!(" 53.1 , 8.8 ,-12.5 ".parse::<Georef>(), Ok(Georef { lat: 53.1, lon: 8.8, bearing: -12.5 }));
    }
}
