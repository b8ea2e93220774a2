#include "io/render/Snapshot.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSetMapper.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkUnstructuredGrid.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace regolith::io {

namespace {

vtkSmartPointer<vtkUnstructuredGrid> readGrid(std::string const& path) {
    if (!std::filesystem::is_regular_file(path))
        throw core::InputError(fmt::format("cannot read '{}': no such file", path));
    vtkSmartPointer<vtkUnstructuredGrid> grid;
    if (std::string_view(path).ends_with(".pvtu")) {
        vtkNew<vtkXMLPUnstructuredGridReader> reader;
        reader->SetFileName(path.c_str());
        reader->Update();
        grid = reader->GetOutput();
    } else {
        vtkNew<vtkXMLUnstructuredGridReader> reader;
        reader->SetFileName(path.c_str());
        reader->Update();
        grid = reader->GetOutput();
    }
    if (grid == nullptr)
        throw core::InputError(fmt::format("cannot read '{}' as VTK unstructured grid", path));
    return grid;
}

/// Adds point array "speed" = |velocity| (zero without a velocity array).
void addSpeed(vtkUnstructuredGrid* grid) {
    vtkNew<vtkDoubleArray> speed;
    speed->SetName("speed");
    vtkDataArray* v = grid->GetPointData()->GetArray("velocity");
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
        double s = 0.0;
        if (v != nullptr) {
            std::array<double, 3> x{};
            v->GetTuple(i, x.data());
            s = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        }
        speed->InsertNextValue(s);
    }
    grid->GetPointData()->AddArray(speed);
}

vtkNew<vtkLookupTable> blueToRed(double low, double high) {
    vtkNew<vtkLookupTable> lut;
    lut->SetHueRange(0.667, 0.0);
    lut->SetTableRange(low, high > low ? high : low + 1.0);
    lut->Build();
    return lut;
}

} // namespace

void renderSnapshot(SnapshotOptions const& options) {
    // Without a display VTK's X window aborts the process; say what to do instead.
    if (std::getenv("DISPLAY") == nullptr)
        throw core::InputError("no X display for VTK's off-screen rendering: run under "
                               "xvfb-run (Debian package xvfb)");
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(1.0, 1.0, 1.0);

    auto const grains = readGrid(options.particles);
    addSpeed(grains);
    std::array<double, 2> speed{0.0, 1.0};
    grains->GetPointData()->GetArray("speed")->GetRange(speed.data());
    vtkNew<vtkSphereSource> sphere; // radius 0.5: scale factor 2 makes it the grain's radius
    sphere->SetThetaResolution(16);
    sphere->SetPhiResolution(12);
    vtkNew<vtkGlyph3DMapper> glyphs;
    glyphs->SetInputData(grains);
    glyphs->SetSourceConnection(sphere->GetOutputPort());
    if (grains->GetPointData()->GetArray("radius") != nullptr) {
        glyphs->SetScaleArray("radius");
        glyphs->SetScaleModeToScaleByMagnitude();
        glyphs->SetScaleFactor(2.0);
    }
    glyphs->SetScalarModeToUsePointFieldData();
    glyphs->SelectColorArray("speed");
    glyphs->SetLookupTable(blueToRed(speed[0], speed[1]));
    glyphs->UseLookupTableScalarRangeOn();
    vtkNew<vtkActor> grainActor;
    grainActor->SetMapper(glyphs);
    renderer->AddActor(grainActor);

    if (!options.blocks.empty()) {
        auto const blocks = readGrid(options.blocks);
        std::array<double, 2> ranks{0.0, 1.0};
        if (vtkDataArray* owner = blocks->GetCellData()->GetArray("owner_rank"))
            owner->GetRange(ranks.data());
        vtkNew<vtkDataSetMapper> outline;
        outline->SetInputData(blocks);
        outline->SetScalarModeToUseCellFieldData();
        outline->SelectColorArray("owner_rank");
        vtkNew<vtkLookupTable> rankColours;
        rankColours->SetHueRange(0.0, 0.8);
        rankColours->SetTableRange(ranks[0], ranks[1] > ranks[0] ? ranks[1] : ranks[0] + 1.0);
        rankColours->Build();
        outline->SetLookupTable(rankColours);
        outline->UseLookupTableScalarRangeOn();
        vtkNew<vtkActor> blockActor;
        blockActor->SetMapper(outline);
        blockActor->GetProperty()->SetRepresentationToWireframe();
        blockActor->GetProperty()->SetLineWidth(2.0);
        renderer->AddActor(blockActor);
    }

    renderer->ResetCamera();
    renderer->GetActiveCamera()->Azimuth(30.0);
    renderer->GetActiveCamera()->Elevation(25.0);
    renderer->GetActiveCamera()->Zoom(1.3);
    renderer->ResetCameraClippingRange();
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(options.width, options.height);
    window->AddRenderer(renderer);
    window->Render();
    vtkNew<vtkWindowToImageFilter> image;
    image->SetInput(window);
    image->Update();
    vtkNew<vtkPNGWriter> png;
    png->SetFileName(options.png.c_str());
    png->SetInputConnection(image->GetOutputPort());
    png->Write();
    if (png->GetErrorCode() != 0 || !std::filesystem::is_regular_file(options.png))
        throw core::InputError(fmt::format("cannot write '{}'", options.png));
}

} // namespace regolith::io
