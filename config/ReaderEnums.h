#pragma once

// Internal to config/: the scenario's enumerations as they are spelled in JSON (shared by the
// section readers and layerKindName / operationName).
#include "config/ReaderSupport.h"

namespace kiosk::config::reader {

// ---------------------------------------------------------------------------------------------
// Enumerations as they are spelled in JSON.

inline const EnumTable<LayerKind> kLayerKinds = {{"thematic", LayerKind::Thematic},
                                                 {"luminance", LayerKind::Luminance},
                                                 {"topographic", LayerKind::Topographic},
                                                 {"visibility", LayerKind::Visibility},
                                                 {"data", LayerKind::Data},
                                                 {"sequence", LayerKind::Sequence},
                                                 {"normals", LayerKind::Normals},
                                                 {"maximum", LayerKind::Maximum},
                                                 {"arrival", LayerKind::Arrival},
                                                 {"duration", LayerKind::Duration},
                                                 {"hazard", LayerKind::Hazard},
                                                 {"difference", LayerKind::Difference}};
inline const EnumTable<OperationType> kOperations = {
    {"opacity", OperationType::Opacity}, {"blend", OperationType::Blend},
    {"add", OperationType::Add},         {"modulate", OperationType::Modulate},
    {"mask", OperationType::Mask},       {"replace", OperationType::Replace}};
inline const EnumTable<TerrainReference> kTerrainReferences = {{"lod", TerrainReference::Lod},
                                                               {"full", TerrainReference::Full}};
inline const EnumTable<TextureCompression> kTextureCompressions = {
    {"auto", TextureCompression::Auto},
    {"astc", TextureCompression::Astc},
    {"off", TextureCompression::Off}};
inline const EnumTable<SequenceInterpolation> kInterpolations = {
    {"data", SequenceInterpolation::Data},
    {"none", SequenceInterpolation::None},
    {"arrival", SequenceInterpolation::Arrival}};
inline const EnumTable<color::Space> kSpaces = {{"srgb", color::Space::Srgb},
                                                {"linear", color::Space::Linear},
                                                {"lab", color::Space::Lab},
                                                {"msh", color::Space::Msh}};
inline const EnumTable<RangeBehaviour> kRanges = {{"loop", RangeBehaviour::Loop},
                                                  {"clamp", RangeBehaviour::Clamp},
                                                  {"unbounded", RangeBehaviour::Unbounded}};
inline const EnumTable<LensKind> kLensKinds = {{"highlight", LensKind::Highlight},
                                               {"visibility", LensKind::Visibility},
                                               {"comparison", LensKind::Comparison}};
inline const EnumTable<LensShape> kLensShapes = {
    {"circle", LensShape::Circle}, {"ellipse", LensShape::Ellipse}, {"swipe", LensShape::Swipe}};
inline const EnumTable<BlendFactor> kBlendFactors = {
    {"zero", BlendFactor::Zero},         {"one", BlendFactor::One},
    {"srcColor", BlendFactor::SrcColor}, {"oneMinusSrcColor", BlendFactor::OneMinusSrcColor},
    {"dstColor", BlendFactor::DstColor}, {"oneMinusDstColor", BlendFactor::OneMinusDstColor},
    {"srcAlpha", BlendFactor::SrcAlpha}, {"oneMinusSrcAlpha", BlendFactor::OneMinusSrcAlpha},
    {"dstAlpha", BlendFactor::DstAlpha}, {"oneMinusDstAlpha", BlendFactor::OneMinusDstAlpha}};
inline const EnumTable<CameraInterpolation> kCameraInterpolations = {
    {"smooth", CameraInterpolation::Smooth},
    {"linear", CameraInterpolation::Linear},
    {"step", CameraInterpolation::Step}};
inline const EnumTable<Corner> kCorners = {{"top-left", Corner::TopLeft},
                                           {"top-right", Corner::TopRight},
                                           {"bottom-left", Corner::BottomLeft},
                                           {"bottom-right", Corner::BottomRight},
                                           {"top", Corner::Top},
                                           {"bottom", Corner::Bottom}};

}  // namespace kiosk::config::reader
