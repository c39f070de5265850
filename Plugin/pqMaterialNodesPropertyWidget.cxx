#include "pqMaterialNodesPropertyWidget.h"
pqMaterialNodesPropertyWidget::pqMaterialNodesPropertyWidget(vtkSMProxy* proxy, vtkSMProperty*, QWidget* parent)
  : Superclass(proxy, parent)
{
}
pqMaterialNodesPropertyWidget::~pqMaterialNodesPropertyWidget() = default;
