// mmv::CheckMultiMaterialInputs: the verdict vtkMultiMaterialVolumeMapper
// reports for each kind of input it cannot shade with materials (TestBadInput
// renders the same inputs through the mapper).
#include "mmvTestScenes.h"
#include "mmvTestWindow.h"

#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMultiMaterialInputCheck.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <gtest/gtest.h>

namespace
{
// A mapper, a volume and a renderer in an OpenGL window (never rendered: the
// checks look at the inputs only).
struct CheckScene
{
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkRenderWindow> Window = mmvtest::NewRenderWindow();

  CheckScene()
  {
    this->Window->AddRenderer(this->Renderer);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(this->Property);
  }
  mmv::InputCheck Check(vtkImageData* image)
  {
    this->Mapper->SetInputData(image);
    return mmv::CheckMultiMaterialInputs(this->Mapper, this->Renderer, this->Volume);
  }
};

vtkSmartPointer<vtkImageData> Ramp(int dims)
{
  return mmvtest::MakeVolume(dims, [](int i, int, int) { return static_cast<float>(i); });
}

vtkSmartPointer<vtkFloatArray> Filled(int components, vtkIdType tuples, float value)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  array->FillValue(value);
  return array;
}

void ExpectFallback(const mmv::InputCheck& check, const std::string& reason)
{
  EXPECT_FALSE(check.Supported);
  EXPECT_EQ(check.Reason, reason);
  EXPECT_EQ(check.Image, nullptr);
  EXPECT_EQ(check.Scalars, nullptr);
}
}

TEST(InputCheck, VolumeOfOneComponentPointScalarsIsSupported)
{
  CheckScene scene;
  auto image = Ramp(4);
  const mmv::InputCheck check = scene.Check(image);
  EXPECT_TRUE(check.Supported);
  EXPECT_EQ(check.Reason, "");
  EXPECT_EQ(check.Caveat, "");
  EXPECT_EQ(check.Image, image.Get());
  EXPECT_EQ(check.Scalars, image->GetPointData()->GetScalars());
  EXPECT_EQ(check.Context, vtkOpenGLRenderWindow::SafeDownCast(scene.Window));
}

TEST(InputCheck, OtherBlendModesAndMissingInputsFallBackSilently)
{
  // The base class renders them (and reports missing scalars itself).
  CheckScene scene;
  scene.Mapper->SetBlendModeToMaximumIntensity();
  ExpectFallback(scene.Check(Ramp(4)), "");
  CheckScene noInput;
  ExpectFallback(
    mmv::CheckMultiMaterialInputs(noInput.Mapper, noInput.Renderer, noInput.Volume), "");
  scene.Mapper->SetBlendModeToComposite();
  auto unscaled = Ramp(4);
  unscaled->GetPointData()->SetScalars(nullptr);
  ExpectFallback(scene.Check(unscaled), "");
}

TEST(InputCheck, EmptyShortFlatCellAndMultiComponentScalarsSayWhy)
{
  CheckScene scene;
  const std::string nothing =
    "the input has no points or fewer scalars than points; nothing to shade";
  auto empty = vtkSmartPointer<vtkImageData>::New();
  empty->SetExtent(0, -1, 0, -1, 0, -1);
  vtkNew<vtkFloatArray> none;
  empty->GetPointData()->SetScalars(none);
  ExpectFallback(scene.Check(empty), nothing);

  auto shortScalars = Ramp(4);
  shortScalars->GetPointData()->GetScalars()->SetNumberOfTuples(63);
  ExpectFallback(scene.Check(shortScalars), nothing);

  auto flatCells = vtkSmartPointer<vtkImageData>::New();
  flatCells->SetDimensions(4, 4, 1);
  flatCells->GetCellData()->SetScalars(Filled(1, 9, 1.0f));
  ExpectFallback(scene.Check(flatCells),
    "cell scalars on an image with a single point along an axis have no volume to render; "
    "using VTK's shading");

  // Dependent components (direct colour) are not fields.
  auto rgb = Ramp(4);
  rgb->GetPointData()->SetScalars(Filled(3, 64, 0.5f));
  scene.Property->IndependentComponentsOff();
  const mmv::InputCheck check = scene.Check(rgb);
  ExpectFallback(check,
    "multi-material shading needs one-component scalars or independent components (for "
    "vectors, set the mapper's VectorMode, or colour by Magnitude or a component); using VTK's "
    "shading");
  EXPECT_EQ(check.Caveat, "");
  // Independent ones are: 2-4 fields.
  scene.Property->IndependentComponentsOn();
  EXPECT_TRUE(scene.Check(rgb).Supported);
  auto five = Ramp(4);
  five->GetPointData()->SetScalars(Filled(5, 64, 0.5f));
  ExpectFallback(scene.Check(five),
    "the scalars have 5 components: at most 4 fields can be shaded together; using VTK's "
    "shading");
}

TEST(InputCheck, CellScalarsAreSupportedAndMarkedAsCellData)
{
  CheckScene scene;
  auto cells = vtkSmartPointer<vtkImageData>::New();
  cells->SetDimensions(4, 4, 4);
  cells->GetCellData()->SetScalars(Filled(1, 27, 1.0f));
  const mmv::InputCheck check = scene.Check(cells);
  EXPECT_TRUE(check.Supported);
  EXPECT_TRUE(check.CellData);
  EXPECT_EQ(check.Scalars, cells->GetCellData()->GetScalars());
  EXPECT_FALSE(scene.Check(Ramp(4)).CellData);
}

TEST(InputCheck, SingleSliceIsShadedWithACaveat)
{
  CheckScene scene;
  auto slice = vtkSmartPointer<vtkImageData>::New();
  slice->SetDimensions(4, 4, 1);
  slice->GetPointData()->SetScalars(Filled(1, 16, 2.0f));
  const std::string caveat = "the input is a single slice (one point along an axis): it has no "
                             "thickness and may render empty";
  mmv::InputCheck check = scene.Check(slice);
  EXPECT_TRUE(check.Supported);
  EXPECT_EQ(check.Caveat, caveat);
  // A later check still fails it, and the caveat comes with the reason.
  scene.Property->SetTransferFunctionModeTo2D();
  check = scene.Check(slice);
  ExpectFallback(check, "multi-material shading needs a 1D transfer function; using VTK's shading");
  EXPECT_EQ(check.Caveat, caveat);
}
