// StoreWriter's schema: the GeoPackage tables, geokiosk's own, and their extension rows
// (docs/store-format.md).
#include "runtime/io/StoreWriter.h"

namespace kiosk::io {

namespace {

constexpr const char* kSchema = R"SQL(
CREATE TABLE IF NOT EXISTS gpkg_spatial_ref_sys (srs_name TEXT NOT NULL, srs_id INTEGER NOT NULL
  PRIMARY KEY, organization TEXT NOT NULL, organization_coordsys_id INTEGER NOT NULL,
  definition TEXT NOT NULL, description TEXT);
INSERT OR IGNORE INTO gpkg_spatial_ref_sys VALUES ('Undefined cartesian SRS', -1, 'NONE', -1,
  'undefined', 'undefined cartesian coordinate reference system');
INSERT OR IGNORE INTO gpkg_spatial_ref_sys VALUES ('Undefined geographic SRS', 0, 'NONE', 0,
  'undefined', 'undefined geographic coordinate reference system');
INSERT OR IGNORE INTO gpkg_spatial_ref_sys VALUES ('WGS 84 geodetic', 4326, 'EPSG', 4326,
  'GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563,AUTHORITY["EPSG","7030"]],AUTHORITY["EPSG","6326"]],PRIMEM["Greenwich",0,AUTHORITY["EPSG","8901"]],UNIT["degree",0.0174532925199433,AUTHORITY["EPSG","9122"]],AXIS["Latitude",NORTH],AXIS["Longitude",EAST],AUTHORITY["EPSG","4326"]]',
  'longitude/latitude coordinates in decimal degrees on the WGS 84 spheroid');
INSERT OR IGNORE INTO gpkg_spatial_ref_sys VALUES ('WGS 84 3D', 4979, 'EPSG', 4979,
  'GEODCRS["WGS 84",DATUM["World Geodetic System 1984",ELLIPSOID["WGS 84",6378137,298.257223563,LENGTHUNIT["metre",1.0]]],CS[ellipsoidal,3],AXIS["latitude",north,ORDER[1],ANGLEUNIT["degree",0.01745329252]],AXIS["longitude",east,ORDER[2],ANGLEUNIT["degree",0.01745329252]],AXIS["ellipsoidal height",up,ORDER[3],LENGTHUNIT["metre",1.0]],ID["EPSG",4979]]',
  'required by the 2D gridded coverage extension');
CREATE TABLE IF NOT EXISTS gpkg_contents (table_name TEXT NOT NULL PRIMARY KEY, data_type TEXT
  NOT NULL, identifier TEXT UNIQUE, description TEXT DEFAULT '', last_change DATETIME NOT NULL
  DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ','now')), min_x DOUBLE, min_y DOUBLE, max_x DOUBLE,
  max_y DOUBLE, srs_id INTEGER, CONSTRAINT fk_gc_r_srs_id FOREIGN KEY (srs_id) REFERENCES
  gpkg_spatial_ref_sys(srs_id));
CREATE TABLE IF NOT EXISTS gpkg_tile_matrix_set (table_name TEXT NOT NULL PRIMARY KEY, srs_id
  INTEGER NOT NULL, min_x DOUBLE NOT NULL, min_y DOUBLE NOT NULL, max_x DOUBLE NOT NULL, max_y
  DOUBLE NOT NULL, CONSTRAINT fk_gtms_table_name FOREIGN KEY (table_name) REFERENCES
  gpkg_contents(table_name), CONSTRAINT fk_gtms_srs FOREIGN KEY (srs_id) REFERENCES
  gpkg_spatial_ref_sys (srs_id));
CREATE TABLE IF NOT EXISTS gpkg_tile_matrix (table_name TEXT NOT NULL, zoom_level INTEGER NOT
  NULL, matrix_width INTEGER NOT NULL, matrix_height INTEGER NOT NULL, tile_width INTEGER NOT
  NULL, tile_height INTEGER NOT NULL, pixel_x_size DOUBLE NOT NULL, pixel_y_size DOUBLE NOT NULL,
  CONSTRAINT pk_ttm PRIMARY KEY (table_name, zoom_level), CONSTRAINT fk_tmm_table_name FOREIGN
  KEY (table_name) REFERENCES gpkg_contents(table_name));
CREATE TABLE IF NOT EXISTS gpkg_extensions (table_name TEXT, column_name TEXT, extension_name
  TEXT NOT NULL, definition TEXT NOT NULL, scope TEXT NOT NULL, CONSTRAINT ge_tce UNIQUE
  (table_name, column_name, extension_name));
CREATE TABLE IF NOT EXISTS gpkg_2d_gridded_coverage_ancillary (id INTEGER PRIMARY KEY
  AUTOINCREMENT, tile_matrix_set_name TEXT NOT NULL UNIQUE, datatype TEXT NOT NULL DEFAULT
  'integer', scale REAL NOT NULL DEFAULT 1.0, offset REAL NOT NULL DEFAULT 0.0, precision REAL
  DEFAULT 1.0, data_null REAL, grid_cell_encoding TEXT DEFAULT 'grid-value-is-center', uom TEXT,
  field_name TEXT DEFAULT 'Height', quantity_definition TEXT DEFAULT 'Height', CONSTRAINT
  fk_g2dgtct_name FOREIGN KEY('tile_matrix_set_name') REFERENCES gpkg_tile_matrix_set
  (table_name), CHECK (datatype in ('integer','float')));
CREATE TABLE IF NOT EXISTS gpkg_2d_gridded_tile_ancillary (id INTEGER PRIMARY KEY
  AUTOINCREMENT, tpudt_name TEXT NOT NULL, tpudt_id INTEGER NOT NULL, scale REAL NOT NULL
  DEFAULT 1.0, offset REAL NOT NULL DEFAULT 0.0, min REAL DEFAULT NULL, max REAL DEFAULT NULL,
  mean REAL DEFAULT NULL, std_dev REAL DEFAULT NULL, CONSTRAINT fk_g2dgtat_name FOREIGN KEY
  (tpudt_name) REFERENCES gpkg_contents(table_name), UNIQUE (tpudt_name, tpudt_id));
CREATE TABLE IF NOT EXISTS kiosk_grid (id INTEGER PRIMARY KEY CHECK (id = 1), srs_id INTEGER NOT
  NULL, min_x DOUBLE NOT NULL, min_y DOUBLE NOT NULL, max_x DOUBLE NOT NULL, max_y DOUBLE NOT
  NULL, tile_width INTEGER NOT NULL, tile_height INTEGER NOT NULL, levels INTEGER NOT NULL,
  finest_pixel_size DOUBLE NOT NULL);
CREATE TABLE IF NOT EXISTS kiosk_layers (table_name TEXT NOT NULL PRIMARY KEY, kind TEXT NOT
  NULL, units TEXT NOT NULL DEFAULT '', min_value DOUBLE, max_value DOUBLE, nodata DOUBLE,
  data_min_x DOUBLE, data_min_y DOUBLE, data_max_x DOUBLE, data_max_y DOUBLE, levels INTEGER,
  tile_count INTEGER, precision DOUBLE, description TEXT DEFAULT '');
CREATE TABLE IF NOT EXISTS kiosk_tile_stats (table_name TEXT NOT NULL, zoom_level INTEGER NOT
  NULL, tile_column INTEGER NOT NULL, tile_row INTEGER NOT NULL, min_value DOUBLE NOT NULL,
  max_value DOUBLE NOT NULL, geometric_error DOUBLE NOT NULL, border_posts BLOB, PRIMARY KEY
  (table_name, zoom_level, tile_column, tile_row)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS kiosk_sequences (name TEXT NOT NULL PRIMARY KEY, units TEXT NOT NULL
  DEFAULT '', variable TEXT NOT NULL DEFAULT '', categorical INTEGER NOT NULL DEFAULT 0, nodata
  DOUBLE, description TEXT DEFAULT '');
CREATE TABLE IF NOT EXISTS kiosk_sequence_frames (sequence_name TEXT NOT NULL, frame_index
  INTEGER NOT NULL, time_utc TEXT NOT NULL, time_epoch DOUBLE NOT NULL, table_name TEXT NOT NULL
  UNIQUE, min_value DOUBLE, max_value DOUBLE, PRIMARY KEY (sequence_name, frame_index));
CREATE TABLE IF NOT EXISTS gpkg_geometry_columns (table_name TEXT NOT NULL, column_name TEXT NOT
  NULL, geometry_type_name TEXT NOT NULL, srs_id INTEGER NOT NULL, z TINYINT NOT NULL, m TINYINT
  NOT NULL, CONSTRAINT pk_geom_cols PRIMARY KEY (table_name, column_name), CONSTRAINT
  uk_gc_table_name UNIQUE (table_name), CONSTRAINT fk_gc_tn FOREIGN KEY (table_name) REFERENCES
  gpkg_contents(table_name), CONSTRAINT fk_gc_srs FOREIGN KEY (srs_id) REFERENCES
  gpkg_spatial_ref_sys (srs_id));
CREATE VIEW IF NOT EXISTS kiosk_sequence_times AS SELECT f.rowid AS fid, f.sequence_name AS
  sequence_name, f.frame_index AS frame_index, f.time_utc AS time_utc, f.time_epoch AS
  time_epoch, f.table_name AS table_name, f.min_value AS min_value, f.max_value AS max_value,
  s.units AS units FROM kiosk_sequence_frames f JOIN kiosk_sequences s ON s.name =
  f.sequence_name;
INSERT OR IGNORE INTO gpkg_contents (table_name, data_type, identifier, description, last_change)
  VALUES ('kiosk_sequence_times', 'attributes', 'kiosk_sequence_times', 'time steps of every '
  || 'sequence: one row per frame with its time and coverage table',
  strftime('%Y-%m-%dT%H:%M:%fZ', 'now'));
)SQL";

}  // namespace

Diagnostics StoreWriter::createSchema() {
    Diagnostics d = mDb.exec(kSchema);
    if (d.hasErrors()) return d;
    const std::string def = kOurDefinition;
    d.append(registerExtension("gpkg_2d_gridded_coverage_ancillary", nullptr, kCoverageExtension,
                               kCoverageDefinition));
    d.append(registerExtension("gpkg_2d_gridded_tile_ancillary", nullptr, kCoverageExtension,
                               kCoverageDefinition));
    d.append(registerExtension(kGridTable, nullptr, kStoreExtension, def + "#kiosk_store"));
    d.append(registerExtension(kLayersTable, nullptr, kStoreExtension, def + "#kiosk_store"));
    d.append(registerExtension(kTileStatsTable, nullptr, kTileStatsExtension,
                               def + "#kiosk_tile_stats"));
    d.append(
        registerExtension(kSequencesTable, nullptr, kSequencesExtension, def + "#kiosk_sequences"));
    d.append(
        registerExtension(kFramesTable, nullptr, kSequencesExtension, def + "#kiosk_sequences"));
    return d;
}

Diagnostics StoreWriter::registerExtension(const std::string& table, const char* column,
                                           const std::string& extension,
                                           const std::string& definition) {
    Diagnostics d;
    // NULL column names never collide in the UNIQUE constraint, so test for the row explicitly
    // (stores are re-opened for every append).
    auto st = mDb.prepare(
        "INSERT INTO gpkg_extensions SELECT ?1, ?2, ?3, ?4, 'read-write' WHERE "
        "NOT EXISTS (SELECT 1 FROM gpkg_extensions WHERE table_name IS ?1 AND "
        "column_name IS ?2 AND extension_name = ?3)");
    if (!st) return st.diagnostics;
    st->bind(1, std::string_view(table));
    if (column)
        st->bind(2, std::string_view(column));
    else
        st->bindNull(2);
    st->bind(3, std::string_view(extension));
    st->bind(4, std::string_view(definition));
    if (st->step() != SQLITE_DONE)
        d.add(mDb.error("STORE_SQL", "gpkg_extensions", "cannot register " + extension));
    return d;
}

}  // namespace kiosk::io
