#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

// Colour-space conversions for transfer functions. Pure functions, no state, any thread.
// Reference white is D65 (sRGB's); Lab uses the CIE 1976 definition; Msh is Moreland's polar
// form of Lab ("Diverging Color Maps for Scientific Visualization", 2009).
namespace kiosk::color {

/** @brief A colour with sRGB-encoded components in [0,1] and straight (not premultiplied) alpha. */
struct Rgba {
    float r = 0, g = 0, b = 0, a = 1;
    friend bool operator==(const Rgba&, const Rgba&) = default;
};

using Vec3 = std::array<double, 3>;

/** @brief Interpolation space of a transfer function. */
enum class Space { Srgb, Linear, Lab, Msh };

/** @brief "srgb" | "linear" | "lab" | "msh"; nullopt for anything else. */
std::optional<Space> parseSpace(std::string_view name);
const char* spaceName(Space s) noexcept;

double srgbToLinear(double c) noexcept;  ///< IEC 61966-2-1 decoding of one channel
double linearToSrgb(double c) noexcept;  ///< encoding; input clamped to [0,1]

Vec3 linearToXyz(const Vec3& rgb) noexcept;  ///< linear sRGB (D65) -> XYZ, Y of white = 1
Vec3 xyzToLinear(const Vec3& xyz) noexcept;
Vec3 xyzToLab(const Vec3& xyz) noexcept;  ///< L in [0,100]
Vec3 labToXyz(const Vec3& lab) noexcept;
Vec3 labToMsh(const Vec3& lab) noexcept;  ///< (M, s, h): magnitude, saturation angle, hue angle
Vec3 mshToLab(const Vec3& msh) noexcept;

/** @brief sRGB-encoded rgb -> the given space's coordinates (Srgb is the identity). */
Vec3 toSpace(const Vec3& srgb, Space space) noexcept;
/** @brief Back to sRGB-encoded rgb; out-of-gamut results are clamped to [0,1]. */
Vec3 fromSpace(const Vec3& coords, Space space) noexcept;

/**
 * @brief Interpolate two sRGB colours in a space; t in [0,1].
 *
 * Srgb/Linear/Lab interpolate coordinates linearly. Msh follows Moreland's algorithm: when both
 * ends are saturated and their hues differ by more than 60 degrees an unsaturated midpoint
 * (M = max(M1, M2, 88)) is inserted, and the hue of an unsaturated end is spun towards the
 * saturated one, which gives the white-centred diverging maps.
 */
Vec3 interpolate(const Vec3& a, const Vec3& b, double t, Space space) noexcept;

/**
 * @brief Parse a colour string: `#rgb`, `#rrggbb`, `#rrggbbaa`, or a name (`transparent`,
 * `white`, `black`, `red`, `green`, `blue`, `yellow`, `cyan`/`aqua`, `magenta`, `gray`/`grey`,
 * `orange`, `brown`, `purple`/`violet`, `indigo`, `navy`, `teal`). Case-insensitive; nullopt on
 * anything else (callers report the error with their own location).
 */
std::optional<Rgba> parseColor(std::string_view text);
/** @brief The names parseColor accepts, for "did you mean" hints. */
const std::array<std::string_view, 18>& colorNames() noexcept;
/** @brief `#rrggbbaa`. */
std::string formatColor(const Rgba& c);

}  // namespace kiosk::color
