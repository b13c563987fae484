#pragma once

// A projected CF NetCDF sequence (time, y, x) written with libnetcdf for the importer tests:
// x/y in metres at cell centres of a north-up grid, a CF time axis, optional units, calendar
// and _FillValue on the data variable.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <netcdf.h>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::import::test {

struct CfSequenceFile {
    std::string variable = "depth";
    int nx = 10, ny = 8;
    double cell = 100;                   ///< metres
    double left = 0, top = 800;          ///< outer edges of the grid
    std::vector<double> times = {0, 1};  ///< in timeUnits
    std::string timeUnits = "hours since 2024-01-01 00:00:00";
    std::string calendar;  ///< none when empty
    std::string units;     ///< of the variable; none when empty
    std::optional<float> fill;
    /** Value of step k at sample i (row-major in the file's y, x order). */
    std::function<float(int k, int i)> value = [](int, int) { return 0.f; };

    void write(const std::filesystem::path& p) const {
        int id, dt, dy, dx, vt, vy, vx, vd;
        ASSERT_EQ(nc_create(p.c_str(), NC_CLOBBER, &id), NC_NOERR);
        nc_def_dim(id, "time", times.size(), &dt);
        nc_def_dim(id, "y", std::size_t(ny), &dy);
        nc_def_dim(id, "x", std::size_t(nx), &dx);
        nc_def_var(id, "time", NC_DOUBLE, 1, &dt, &vt);
        nc_def_var(id, "y", NC_DOUBLE, 1, &dy, &vy);
        nc_def_var(id, "x", NC_DOUBLE, 1, &dx, &vx);
        const int dims[3] = {dt, dy, dx};
        nc_def_var(id, variable.c_str(), NC_FLOAT, 3, dims, &vd);
        nc_put_att_text(id, vt, "units", timeUnits.size(), timeUnits.data());
        if (!calendar.empty())
            nc_put_att_text(id, vt, "calendar", calendar.size(), calendar.data());
        nc_put_att_text(id, vx, "units", 1, "m");
        nc_put_att_text(id, vy, "units", 1, "m");
        nc_put_att_text(id, vx, "standard_name", 23, "projection_x_coordinate");
        nc_put_att_text(id, vy, "standard_name", 23, "projection_y_coordinate");
        if (!units.empty()) nc_put_att_text(id, vd, "units", units.size(), units.data());
        if (fill) nc_put_att_float(id, vd, "_FillValue", NC_FLOAT, 1, &*fill);
        nc_enddef(id);
        std::vector<double> ys(static_cast<std::size_t>(ny)), xs(static_cast<std::size_t>(nx));
        for (int i = 0; i < ny; ++i) ys[std::size_t(i)] = top - cell * (i + 0.5);
        for (int i = 0; i < nx; ++i) xs[std::size_t(i)] = left + cell * (i + 0.5);
        const int n = nx * ny;
        std::vector<float> v(times.size() * std::size_t(n));
        for (std::size_t k = 0; k < times.size(); ++k)
            for (int i = 0; i < n; ++i) v[k * std::size_t(n) + std::size_t(i)] = value(int(k), i);
        nc_put_var_double(id, vt, times.data());
        nc_put_var_double(id, vy, ys.data());
        nc_put_var_double(id, vx, xs.data());
        nc_put_var_float(id, vd, v.data());
        ASSERT_EQ(nc_close(id), NC_NOERR);
    }
};

}  // namespace kiosk::import::test
