#pragma once
// Physical constants of the GNSS interface documents (IS-GPS-200, Galileo OS SIS ICD).
namespace twinslam::gnss {

inline constexpr double kSpeedOfLight = 299792458.0;       // [m/s]
inline constexpr double kEarthRotationRate = 7.2921151467e-5;  // WGS84 Earth rotation rate [rad/s]
inline constexpr double kGmGps = 3.986005e14;               // GPS value of G*M_earth [m^3/s^2]
inline constexpr double kGmGalileo = 3.986004418e14;        // Galileo value [m^3/s^2]

// Satellite systems, with the numbers the smartLoc dataset (and RTKLIB) use for them.
enum class SatSystem : int { kGps = 1, kSbas = 2, kGlonass = 4, kGalileo = 8, kQzss = 16, kBeidou = 32 };

// "GPS", "Galileo", ...; "system N" for a number this enum does not name.
const char* system_name(SatSystem system);

}  // namespace twinslam::gnss
