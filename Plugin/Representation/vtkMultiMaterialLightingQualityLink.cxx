// Keeps a display's "Lighting Quality" and the irradiance internals it sets
// equal in the server manager, wherever a server manager runs (the GUI,
// pvpython).
//
// The representation applies mmv::LightingQualityTable itself when
// LightingQuality arrives; if only that happened, the internal properties
// would still hold their old values, a state file would save values the
// renderer does not use, and setting an internal back to its old value from
// Python would push nothing. So, as vtkMultiMaterialFirstUse.cxx does, this
// observes the proxy manager's PropertyModifiedEvent: when a display's
// LightingQuality becomes Fast, Balanced or Exact, the internals are set to
// its row; when an internal is set to a value its level does not have, the
// level becomes Custom. State files are left as they were saved.
#include "vtkCommand.h"
#include "vtkMultiMaterialLightingQuality.h"
#include "vtkMultiMaterialPropertyObserver.h"
#include "vtkNew.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"

#include <cstring>
#include <string>

namespace
{
constexpr const char* QualityProperty = "LightingQuality";

// The internals of a row, by property name, as doubles.
struct Internal
{
  const char* Name;
  double (*Value)(const mmv::LightingQualitySettings&);
};
const Internal Internals[] = {
  { "ShadowEstimation",
    [](const mmv::LightingQualitySettings& r) { return double(r.ShadowEstimation); } },
  { "PiecewiseShadowSlices",
    [](const mmv::LightingQualitySettings& r) { return double(r.PiecewiseShadowSlices); } },
  { "ExponentialDiffusion",
    [](const mmv::LightingQualitySettings& r) { return double(r.ExponentialDiffusion); } },
  { "PieceIrradianceOnly",
    [](const mmv::LightingQualitySettings& r) { return double(r.PieceIrradianceOnly); } },
  { "LightDirectionTolerance",
    [](const mmv::LightingQualitySettings& r) { return r.LightDirectionTolerance; } },
  { "ReflectionVisibility",
    [](const mmv::LightingQualitySettings& r) { return double(r.ReflectionVisibility); } },
  { "IrradianceErrorBound",
    [](const mmv::LightingQualitySettings& r) { return r.IrradianceErrorBound; } },
  { "IrradianceMemoryMB",
    [](const mmv::LightingQualitySettings& r) { return r.IrradianceMemoryMB; } },
  { "IrradianceScale", [](const mmv::LightingQualitySettings& r) { return r.IrradianceScale; } },
  { "DimLightCoarsening",
    [](const mmv::LightingQualitySettings& r) { return double(r.DimLightCoarsening); } },
};

const Internal* FindInternal(const char* name)
{
  for (const Internal& internal : Internals)
  {
    if (strcmp(internal.Name, name) == 0)
    {
      return &internal;
    }
  }
  return nullptr;
}

class vtkMultiMaterialLightingQualityObserver : public vtkCommand
{
public:
  static vtkMultiMaterialLightingQualityObserver* New()
  {
    return new vtkMultiMaterialLightingQualityObserver;
  }

  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    auto* info = static_cast<vtkSMProxyManager::ModifiedPropertyInformation*>(callData);
    if (this->Busy || !info || !info->Proxy || !info->PropertyName)
    {
      return;
    }
    vtkSMProxy* display = info->Proxy;
    vtkSMSessionProxyManager* pxm = display->GetSessionProxyManager();
    if (!display->GetProperty(QualityProperty) || (pxm && pxm->GetInLoadXMLState()))
    {
      return;
    }
    const int level = vtkSMPropertyHelper(display, QualityProperty).GetAsInt();
    const mmv::LightingQualitySettings* row = mmv::GetLightingQualitySettings(level);
    this->Busy = true; // the properties set below come back here
    if (strcmp(info->PropertyName, QualityProperty) == 0)
    {
      if (row)
      {
        for (const Internal& internal : Internals)
        {
          if (display->GetProperty(internal.Name) &&
            vtkSMPropertyHelper(display, internal.Name).GetAsDouble() != internal.Value(*row))
          {
            vtkSMPropertyHelper(display, internal.Name).Set(internal.Value(*row));
          }
        }
      }
    }
    else if (const Internal* internal = FindInternal(info->PropertyName))
    {
      if (row &&
        vtkSMPropertyHelper(display, internal->Name).GetAsDouble() != internal->Value(*row))
      {
        vtkSMPropertyHelper(display, QualityProperty).Set(mmv::LightingQualityCustom);
      }
    }
    this->Busy = false;
  }

private:
  bool Busy = false;
};

const mmv::PropertyObserverRegistration<vtkMultiMaterialLightingQualityObserver> Registration;
}
