// Peer harness: VTK 9.1 (Debian libvtk9-dev). vtkSTLReader / vtkPLYReader /
// vtkOBJReader, then vtkMassProperties. Prints:
//   vtk VOLUME LOAD_SECONDS VOLUME_SECONDS(median of 5)
#include <vtkAlgorithm.h>
#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>

#include <cstdio>
#include <string>

#include "timing.hpp"

int main(int argc, char** argv) {
    if (argc != 2) return 1;
    const std::string file = argv[1];
    const auto t0 = std::chrono::steady_clock::now();
    vtkSmartPointer<vtkPolyData> poly;
    auto ends = [&](const char* s) { return file.size() >= std::string(s).size() && file.rfind(s) == file.size() - std::string(s).size(); };
    if (ends(".ply")) {
        vtkNew<vtkPLYReader> r;
        r->SetFileName(file.c_str());
        r->Update();
        poly = r->GetOutput();
    } else if (ends(".obj")) {
        vtkNew<vtkOBJReader> r;
        r->SetFileName(file.c_str());
        r->Update();
        poly = r->GetOutput();
    } else {
        vtkNew<vtkSTLReader> r;
        r->SetFileName(file.c_str());
        r->Update();
        poly = r->GetOutput();
    }
    auto volume = [&] {
        vtkNew<vtkMassProperties> mp;
        mp->SetInputData(poly);
        mp->Update();
        return mp->GetVolume();
    };
    double v = volume();
    const double load = peers::seconds_since(t0);
    const double vol_s = peers::median_seconds(5, volume, &v);
    std::printf("vtk %.17g %.6f %.6f %lld\n", v, load, vol_s, static_cast<long long>(poly->GetNumberOfCells()));
    return 0;
}
