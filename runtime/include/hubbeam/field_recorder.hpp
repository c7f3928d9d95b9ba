// The fields along the beam at chosen times, written as a CSV beside a run's rows (hubbeam run --fields-at).
#pragma once

#include <hubbeam/config.hpp>
#include <hubbeam/fields.hpp>
#include <memory>
#include <string>
#include <vector>

#include <hubbeam/csv_columns.hpp>

namespace hubbeam {

class CsvWriter;

/// The fields along the beam at chosen times, written as a second CSV by hubbeam run (docs/cli.md "hubbeam
/// run"): at the first row at or after each time, u_y, u_x, slope, curvature, bending moment and axial force at
/// `points` equally spaced abscissae, plus both sides of each interior piece boundary (where FEM's moment jumps).
/// A rotor's fields are every blade's, blade by blade, each line with its blade's number (the column `blade`).
class FieldRecorder {
public:
    /// Opens path (atomically written, CsvWriter); times sorted, within the run. rotor: the blades (their pitch
    /// increments), whose q is laid out by coordinate_layout(key, rotor.blades).
    FieldRecorder(const VariantKey& key, const Parameters& p, std::vector<double> times, int points,
                  const std::string& path, const Rotor& rotor = Rotor{});
    ~FieldRecorder();
    /// The state at a row: records it if it is the first row at or after the next requested time.
    void state(double t, const double* q);
    /// Puts the file in place; false (and error()) if a write failed.
    bool finish();
    const std::string& error() const;
    const std::string& path() const;

    /// The CSV header: the one list of the field CSV's columns, which state() writes in this order and readers
    /// (hubbeam plot moment) look up by name; a beam out of the plane adds u_z, phi, the flapwise moment and the
    /// torque (header_out_of_plane).
    static const char* header()
    {
        static const std::string h =
            csv_header({"t", "x", "uy", "ux", "slope", "curvature", "bending_moment", "axial_force"});
        return h.c_str();
    }
    static const char* header_out_of_plane()
    {
        static const std::string h = std::string(header()) + "," + csv_header({"uz", "phi", "flap_moment", "torque"});
        return h.c_str();
    }
    /// A rotor's header: the blade's number (1 .. N) after t, then the single blade's columns.
    static std::string header_of_rotor(bool out_of_plane)
    {
        const std::string h = out_of_plane ? header_out_of_plane() : header();
        return h.substr(0, 2) + "blade," + h.substr(2);
    }

private:
    /// A blade's values at x (docs/model.md section 12), given u_y''(x): the edgewise moment EI_edge kappa_c that
    /// replaces EI u_y'', and the columns u_z, phi, EI_flap kappa_n and GJ phi'.
    struct BladeValues {
        double edge_moment = 0.0, uz = 0.0, phi = 0.0, flap_moment = 0.0, torque = 0.0;
    };
    /// blade: 0-based, for its coordinates and pitch.
    BladeValues blade_at(const double* q, int blade, double x, double y2) const;
    /// Writes blade's (0-based) lines at t.
    void write_blade(double t, const double* q, int blade);

    CoordinateLayout coordinates_;
    BeamFields fields_;
    bool out_of_plane_, foreshortened_;
    std::vector<double> stations_;  // a profile's, x/L
    Parameters p_;
    int blades_;
    std::vector<double> pitches_;  // each blade's, its increment added
    std::vector<double> times_, xs_;
    std::size_t next_ = 0;
    std::unique_ptr<CsvWriter> csv_;
};

}  // namespace hubbeam
