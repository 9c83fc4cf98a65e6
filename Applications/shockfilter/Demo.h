/**
 * @file   Demo.h
 * @brief  The parts of the "demo" subcommand (DemoImages.cxx: picture and
 *         volume; DemoCommand.cxx: meshes, help, entry point).
 */
#ifndef Demo_h
#define Demo_h

#include "CliFilters.h"

#include <array>
#include <filesystem>

namespace shockcli
{

/// Flow times of the picture demo, and the one shown in before_after.png.
inline constexpr std::array<double, 4> PictureDemoTimes = { 256, 1024, 4096, 16384 };
inline constexpr double PictureDemoShownTime = 4096;
/// Flow time of the volume demo.
inline constexpr double VolumeDemoTime = 4096;
/// Flow times of the mesh demo: the sphere's colours and the rounded box's geometry.
inline constexpr double SphereDemoTime = 1024;
inline constexpr double BoxDemoTime = 2048;

/// An RGB colour, 0..255.
using Rgb = std::array<double, 3>;

/// Creates 'directory' (and parents) if missing; throws if it cannot.
void CreateDirectory(const std::filesystem::path& directory);

/// The 2D part of the demo: picture, sharpened pictures for several t, before/after.
void RunPictureDemo(const std::filesystem::path& directory, const ShockOptions& common);

/// The 3D part of the demo: blurred volume, sharpened at VolumeDemoTime, middle slices side by side.
void RunVolumeDemo(const std::filesystem::path& directory, const ShockOptions& common);

} // namespace shockcli

#endif
